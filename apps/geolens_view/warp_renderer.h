#pragma once
// A WarpMesh drawn on the GPU: its screen positions as vertices, its source positions over the
// image size as texture coordinates, sampling a mipmapped texture of the image with trilinear
// filtering. The circle lenses' outlines are drawn where the warp shows them, in the fragment
// shader (a ring at the circle's radius in source pixels, one screen pixel wide). The heatmap
// overlay draws each triangle in a colour given per triangle (three vertices of its own, so the
// colour does not blend across edges) over the grey of the picture. Two meshes can be held, one
// per pane of a split view, drawn with the same texture.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geolens/io/image.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens::view {

/// How a frame is drawn: where the warp's screen frame lands in the window, and the overlays.
struct DrawSettings {
  int window_width = 0, window_height = 0;  ///< framebuffer, pixels
  /// Window pixel of the warp's screen point s: origin + s * scale.
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double scale = 1;
  /// The window columns [clip_x, clip_x + clip_width) drawn into; clip_width 0: all of them.
  int clip_x = 0, clip_width = 0;
  int pane = 0;  ///< the mesh drawn, 0 or 1
  bool wireframe = false;
  /// The pane's heatmap (set_heat) instead of the picture: per triangle opacity x its colour +
  /// (1 - opacity) x the picture's luminance, as heatmap() (heatmap.h) blends it.
  bool heatmap = false;
  double heat_opacity = 0.75;
  /// Circles to outline: (centre x, centre y, radius), source pixels; at most kMaxOutlines.
  std::vector<Eigen::Vector3d> outlines;
  int selected = -1;  ///< the outline drawn in the selection colour, -1: none
};

class WarpRenderer {
 public:
  static constexpr int kMaxOutlines = 32;
  /// The texture's limits besides GL_MAX_TEXTURE_SIZE: a side most GPUs take, and the bytes of
  /// its texels (mipmaps add a third) that leave room for everything else.
  static constexpr int kMaxTextureSide = 8192;
  static constexpr size_t kTextureBytes = size_t(192) << 20;
  static constexpr int kPanes = 2;

  /// Compiles the shaders; needs a current OpenGL 3.3 core context. Throws std::runtime_error
  /// with the compiler's log if they do not build.
  WarpRenderer();
  ~WarpRenderer();
  WarpRenderer(const WarpRenderer&) = delete;
  WarpRenderer& operator=(const WarpRenderer&) = delete;

  /// Uploads `image` (1 - 4 channels) with its mipmaps; an image larger than the GPU's largest
  /// texture, kMaxTextureSide or kTextureBytes is uploaded at the finest level of its pyramid
  /// that fits, made through a TiledSource.
  void set_image(const Image& image);
  /// The level of the image's pyramid uploaded (0: the image), and its size in texels.
  int texture_level() const { return texture_level_; }
  int texture_width() const { return texture_width_; }
  int texture_height() const { return texture_height_; }
  /// Uploads the triangles of `mesh` (source pixels of the image set last) for `pane`.
  void set_mesh(int pane, const WarpMesh& mesh);
  /// Uploads the heatmap of `mesh` for `pane`: `colours` one per triangle (#F), RGB.
  void set_heat(int pane, const WarpMesh& mesh, const std::vector<std::array<uint8_t, 3>>& colours);
  /// Clears the window (width x height framebuffer pixels) to the background.
  void clear(int width, int height) const;
  /// Draws the mesh of settings.pane into its columns of the window.
  void draw(const DrawSettings& settings) const;

 private:
  // One pane's triangles: indexed for the picture, three vertices each for the heatmap.
  struct Mesh {
    unsigned vao = 0, vbo = 0, ebo = 0, heat_vao = 0, heat_vbo = 0;
    int index_count = 0, heat_count = 0;
  };

  unsigned program_ = 0, texture_ = 0;
  std::array<Mesh, kPanes> panes_;
  int texture_level_ = 0, texture_width_ = 1, texture_height_ = 1;
  int loc_origin_ = -1, loc_scale_ = -1, loc_window_ = -1, loc_size_ = -1, loc_flat_ = -1,
      loc_colour_ = -1, loc_count_ = -1, loc_circles_ = -1, loc_selected_ = -1, loc_heat_ = -1;
};

}  // namespace geolens::view
