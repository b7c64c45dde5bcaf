#pragma once
// What the renderer samples: a raster of texels at several levels of detail, fetched a region
// at a time (an image and its mip pyramid, a tiled image, next tile pyramids, SVG, vector maps
// and 3D scenes rendered to texels).

#include <cstddef>
#include <cstdint>
#include <memory>

namespace geolens {

/// A read-only rectangle of texels of one level: texel (x + i, y + j) of the level, i in
/// [0, width), j in [0, height), has its `channels` 8-bit values at data + j * stride +
/// i * channels. A view into the source's own storage (valid while the source lives, `owner`
/// empty) or a copy that `owner` keeps alive; either way it is safe to read from any thread.
struct TexelRegion {
  const uint8_t* data = nullptr;
  size_t stride = 0;  ///< bytes from one row to the next
  int x = 0, y = 0;   ///< level texel coordinates of data[0]
  int width = 0, height = 0;
  int channels = 0;
  std::shared_ptr<const void> owner;  ///< keeps `data` alive when the source does not

  /// The texel (x, y) of the level, which must lie in the region.
  const uint8_t* at(int texel_x, int texel_y) const {
    return data + size_t(texel_y - y) * stride + size_t(texel_x - x) * size_t(channels);
  }
};

/// A source raster of width() x height() texels at level 0, in source pixels (the unit of
/// WarpMesh::source), with 1 - 4 interleaved 8-bit channels (grey, grey + alpha, RGB, RGBA).
/// Level l is the source seen at 2^-l of its resolution: level_width(l) = ceil(width() / 2^l)
/// by ceil(height() / 2^l) texels, each side halving and rounding up, down to 1 x 1 at
/// levels() - 1, as a mip pyramid does. Texel (i, j) of level l has its centre at source pixel
/// ((i + 0.5) 2^l, (j + 0.5) 2^l), so source point (x, y) is texel coordinate
/// (x 2^-l - 0.5, y 2^-l - 0.5) with texel centres at integers.
///
/// fetch() is the one way to read texels; every implementation makes it safe to call from
/// several threads at once (the renderer's workers do).
class Source {
 public:
  virtual ~Source() = default;

  int width() const { return width_; }  ///< level 0, texels (source pixels)
  int height() const { return height_; }
  int channels() const { return channels_; }
  int levels() const { return levels_; }  ///< >= 1; the last is 1 x 1
  int level_width(int level) const { return ((width_ - 1) >> level) + 1; }  ///< level in range
  int level_height(int level) const { return ((height_ - 1) >> level) + 1; }

  /// The texels [x, x + width) x [y, y + height) of `level` (texel indices). Texels outside
  /// the level repeat its nearest edge texel (clamp-to-edge), so any rectangle can be fetched;
  /// one inside the level may be a view without a copy (the in-memory pyramid's always is).
  /// Throws InvalidInput unless level is in [0, levels()), width and height >= 1 and
  /// width * height <= 2^30.
  TexelRegion fetch(int level, int x, int y, int width, int height) const;

 protected:
  /// Throws InvalidInput (naming `function`) unless width, height >= 1 and channels in [1, 4].
  Source(int width, int height, int channels, const char* function);
  Source(const Source&) = default;
  Source& operator=(const Source&) = default;

  /// fetch() of a rectangle already checked to lie inside `level`.
  virtual TexelRegion fetch_inside(int level, int x, int y, int width, int height) const = 0;

 private:
  int width_, height_, channels_, levels_;
};

}  // namespace geolens
