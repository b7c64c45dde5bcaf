#pragma once
// CPU renderer: draws a WarpMesh, sampling the source through a mip pyramid.

#include <array>
#include <cstdint>
#include <vector>

#include "geolens/io/image.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens {

/// A mip pyramid of a source image: level 0 is the image, each next level halves both sides
/// (rounding up) with a 2x2 box filter, down to 1x1. Built once per source, reused per frame.
class MipPyramid {
 public:
  explicit MipPyramid(const Image& source);
  int levels() const { return int(levels_.size()); }
  const Image& level(int i) const { return levels_[size_t(i)]; }
  int channels() const { return levels_.front().channels; }

  /// Trilinear sample at source-pixel coordinates (x, y) of level 0 (pixel centres at +0.5),
  /// at level-of-detail `lod` (0 = full resolution; clamped to the pyramid), clamp-to-edge.
  /// Writes channels() values in [0, 255] to `out`.
  void sample(double x, double y, double lod, float* out) const;

 private:
  std::vector<Image> levels_;
};

struct RenderOptions {
  int width = 0;                                             ///< output width, pixels (> 0)
  int height = 0;                                            ///< output height, pixels (> 0)
  std::array<uint8_t, 4> background = {255, 255, 255, 255};  ///< for pixels no triangle covers
  int threads = 0;                                           ///< 0 = hardware concurrency
};

/// Rasterizes the screen triangles of `mesh` (screen coordinates scaled from
/// mesh.screen_width x mesh.screen_height to options.width x options.height) and samples the
/// source at the interpolated source coordinate. The level of detail is chosen per triangle
/// from its screen -> source Jacobian, so a minified context does not alias and a magnified
/// focus is smooth. The output has the pyramid's channel count. Coverage is exact (vertices
/// snapped to 1/256 pixel, a top-left style tie rule), so a pixel on an edge shared by two
/// triangles is drawn once; where triangles overlap (a folded map), the later one in F is on top,
/// whatever the thread count. Texels are blended with 8-bit weights, as texture hardware does.
Image render(const WarpMesh& mesh, const MipPyramid& source, const RenderOptions& options);

}  // namespace geolens
