#pragma once
// The in-memory source: an image and its mip pyramid.

#include <vector>

#include "geolens/io/image.h"
#include "geolens/source/source.h"

namespace geolens {

/// A mip pyramid of a source image: level 0 is the image, each next level halves both sides
/// (rounding up) with a 2x2 box filter (downsample.h), down to 1x1. Built once per source,
/// reused per frame. As a Source, fetch() of a region inside a level is a view into the level,
/// without a copy.
class MipPyramid : public Source {
 public:
  /// Throws InvalidInput for an empty image, channels outside [1, 4] or a pixel buffer of the
  /// wrong size.
  explicit MipPyramid(const Image& source);
  const Image& level(int i) const { return levels_[size_t(i)]; }

  /// Trilinear sample at source-pixel coordinates (x, y) of level 0 (pixel centres at +0.5),
  /// at level-of-detail `lod` (0 = full resolution; clamped to the pyramid), clamp-to-edge.
  /// Writes channels() values in [0, 255] to `out`.
  void sample(double x, double y, double lod, float* out) const;

 private:
  TexelRegion fetch_inside(int level, int x, int y, int width, int height) const override;

  std::vector<Image> levels_;
};

}  // namespace geolens
