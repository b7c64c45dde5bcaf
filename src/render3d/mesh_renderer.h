#pragma once
// A software (CPU) renderer for triangle meshes: z-buffered, supersampled, any region of the
// view at any resolution.
//
// Why a renderer of its own rather than Mesa's offscreen OpenGL (OSMesa, or EGL with llvmpipe):
// the sources render one tile at a time, on demand, from the render's worker threads at once,
// with the projection offset to the tile, and the tiles of a level must join exactly. An OpenGL
// context is current on one thread at a time, so GL would need a context per worker or a queue
// to one, plus a read-back per tile, and a library dependency the headless tests must load; a
// CPU rasterizer needs none of it, evaluates every sample from its absolute position in the
// view (so tiles join by construction), and gives the same bytes on every machine, which the
// tests compare. (llvmpipe was not measured against it; it would rasterize on the same cores.)
// Measured (bench/scene3d_bench.cpp, bench/README.md): a 1024 x 1024 view of a 69k-triangle
// mesh in 40 - 80 ms with one sample per pixel, 130 - 270 ms with the default 2 x 2, on 2 cores.

#include <array>
#include <cstdint>
#include <vector>

#include "geolens/io/image.h"
#include "geolens/render3d/camera.h"
#include "render3d/triangle_mesh.h"

namespace geolens {

class ThreadPool;  // core/thread_pool.h

enum class MeshShading {
  flat,    ///< one normal per face: facets show
  smooth,  ///< vertex normals (the file's, or area-weighted from the faces) interpolated
};

/// How a mesh is drawn: one directional light plus ambient light (Blinn-Phong), lit from both
/// sides (an open mesh shows its inside), optional triangle edges, supersampled.
struct MeshStyle {
  MeshShading shading = MeshShading::smooth;
  std::array<uint8_t, 3> colour = {200, 206, 218};      ///< the surface's RGB
  std::array<uint8_t, 3> background = {255, 255, 255};  ///< RGB where no triangle is
  /// Direction towards the light in camera coordinates (x right, y up, z towards the viewer);
  /// non-zero, normalized by the renderer.
  Eigen::Vector3d light{-0.4, 0.6, 0.7};
  double ambient = 0.25;  ///< >= 0
  double diffuse = 0.7;   ///< >= 0
  double specular = 0.2;  ///< >= 0, white highlight
  double shininess = 40;  ///< Blinn-Phong exponent, > 0
  bool edges = false;     ///< draw each triangle's edges
  double edge_width = 1;  ///< frame pixels, > 0: the lines thicken where magnified, like the mesh
  std::array<uint8_t, 3> edge_colour = {40, 40, 48};
  /// Samples per pixel side, in [1, 8]: samples^2 per pixel, averaged (anti-aliasing).
  int samples = 2;
};

/// A mesh seen by a camera in a frame, ready to render any region of the view (camera.h
/// PixelRegion) at any pixel size. Construction transforms the vertices and normals once;
/// render() is const and thread-safe, so tiles render from several threads at once.
class MeshRenderer {
 public:
  /// Places `camera` around the mesh's bounding sphere for a frame_width x frame_height frame
  /// (place_camera). Throws InvalidInput naming "MeshRenderer" for an invalid mesh
  /// (check_triangle_mesh), frame, camera or style.
  MeshRenderer(TriangleMesh mesh, const OrbitCamera& camera, int frame_width, int frame_height,
               const MeshStyle& style = {});

  /// The RGB pixels of `region` (region.width x region.height, 3 channels). Each pixel is the
  /// mean of style.samples^2 samples at the centres of its sub-pixels; a sample shows the
  /// nearest triangle covering it (exact edge tests on the sample's absolute grid position, a
  /// tie rule so that a sample on an edge two triangles share is covered once), shaded with
  /// perspective-correct normals. A triangle with a vertex behind the camera is skipped (it
  /// cannot happen with a fitted camera). `pool`: split the rows over its threads; null = the
  /// calling thread. Throws InvalidInput naming "MeshRenderer::render" for an invalid region.
  Image render(const PixelRegion& region, ThreadPool* pool = nullptr) const;

  const Projection& projection() const { return projection_; }
  int frame_width() const { return frame_width_; }
  int frame_height() const { return frame_height_; }
  Eigen::Index triangles() const { return faces_.rows(); }

 private:
  /// Rows [first_row, first_row + rows) of `region` into `out`, from `triangles` (indices
  /// into F, increasing: those that may cover the rows).
  void render_band(const PixelRegion& region, Image& out, int first_row, int rows,
                   const std::vector<int>& triangles) const;

  Eigen::MatrixXi faces_;
  std::vector<Eigen::Vector2d> screen_;       ///< per vertex, frame pixels
  std::vector<double> inverse_depth_;         ///< per vertex, 1 / depth (<= 0: behind the eye)
  std::vector<Eigen::Vector3d> position_;     ///< per vertex, camera coordinates
  std::vector<Eigen::Vector3d> normal_;       ///< per vertex, camera coordinates
  std::vector<Eigen::Vector3d> face_normal_;  ///< per face, camera coordinates
  MeshStyle style_;
  Eigen::Vector3d light_;
  Projection projection_;
  int frame_width_, frame_height_;
};

}  // namespace geolens
