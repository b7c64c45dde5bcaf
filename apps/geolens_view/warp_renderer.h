#pragma once
// A WarpMesh drawn on the GPU: its screen positions as vertices, its source positions over the
// image size as texture coordinates, sampling a mipmapped texture of the image with trilinear
// filtering. The circle lenses' outlines are drawn where the warp shows them, in the fragment
// shader (a ring at the circle's radius in source pixels, one screen pixel wide).

#include <Eigen/Core>
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
  bool wireframe = false;
  /// Circles to outline: (centre x, centre y, radius), source pixels; at most kMaxOutlines.
  std::vector<Eigen::Vector3d> outlines;
  int selected = -1;  ///< the outline drawn in the selection colour, -1: none
};

class WarpRenderer {
 public:
  static constexpr int kMaxOutlines = 32;

  /// Compiles the shaders; needs a current OpenGL 3.3 core context. Throws std::runtime_error
  /// with the compiler's log if they do not build.
  WarpRenderer();
  ~WarpRenderer();
  WarpRenderer(const WarpRenderer&) = delete;
  WarpRenderer& operator=(const WarpRenderer&) = delete;

  /// Uploads `image` (1 - 4 channels) with its mipmaps; an image larger than the GPU's largest
  /// texture is uploaded at the finest level of its pyramid that fits.
  void set_image(const Image& image);
  /// Uploads the triangles of `mesh` (source pixels of the image set last).
  void set_mesh(const WarpMesh& mesh);
  /// Clears the window to the background and draws the mesh.
  void draw(const DrawSettings& settings) const;
  /// Triangles uploaded, for the panel.
  int triangles() const { return int(index_count_ / 3); }

 private:
  unsigned program_ = 0, vao_ = 0, vbo_ = 0, ebo_ = 0, texture_ = 0;
  int index_count_ = 0;
  int image_width_ = 1, image_height_ = 1;
  int loc_origin_ = -1, loc_scale_ = -1, loc_window_ = -1, loc_size_ = -1, loc_flat_ = -1,
      loc_colour_ = -1, loc_count_ = -1, loc_circles_ = -1, loc_selected_ = -1;
};

}  // namespace geolens::view
