#pragma once
// What the renderer samples: a raster of texels at several levels of detail, fetched a region
// at a time (an image and its mip pyramid, a tiled image, next tile pyramids, SVG, vector maps
// and 3D scenes rendered to texels).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "geolens/io/image.h"

namespace geolens {

/// A read-only rectangle of texels of one level: texel (x + i, y + j) of the level, i in
/// [0, width), j in [0, height), has its `channels` 8-bit values at data + j * stride +
/// i * channels. A view into the source's own storage (valid while the source lives, `owner`
/// empty) or a copy that `owner` keeps alive; either way it is safe to read from any thread.
struct TexelRegion {
  const uint8_t* data = nullptr;  ///< the values of texel (x, y), then the rest of its row
  size_t stride = 0;              ///< bytes from one row to the next
  ///@{
  int x = 0, y = 0;  ///< level texel coordinates of data[0]
  ///@}
  ///@{
  int width = 0, height = 0;  ///< texels, >= 1
  ///@}
  int channels = 0;                   ///< values per texel, the source's: 1 - 4
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

  int width() const { return width_; }        ///< level 0, texels (source pixels)
  int height() const { return height_; }      ///< level 0, texels (source pixels)
  int channels() const { return channels_; }  ///< 8-bit values per texel, 1 - 4
  int levels() const { return levels_; }      ///< >= 1; the last is 1 x 1
  int level_width(int level) const { return ((width_ - 1) >> level) + 1; }    ///< level in range
  int level_height(int level) const { return ((height_ - 1) >> level) + 1; }  ///< level in range

  /// The texels [x, x + width) x [y, y + height) of `level` (texel indices). Texels outside
  /// the level repeat its nearest edge texel (clamp-to-edge), so any rectangle can be fetched;
  /// one inside the level may be a view without a copy (the in-memory pyramid's always is).
  /// Throws InvalidInput unless level is in [0, levels()), width and height >= 1 and
  /// width * height <= 2^30.
  TexelRegion fetch(int level, int x, int y, int width, int height) const;

 protected:
  /// Throws InvalidInput (naming `function`) unless width, height >= 1 and channels in [1, 4].
  Source(int width, int height, int channels, const char* function);
  /// Copied only as the derived class it is, never sliced through a Source.
  ///@{
  Source(const Source&) = default;
  Source& operator=(const Source&) = default;
  ///@}

  /// fetch() of a rectangle already checked to lie inside `level`.
  virtual TexelRegion fetch_inside(int level, int x, int y, int width, int height) const = 0;

 private:
  int width_, height_, channels_, levels_;
};

// The in-memory source: an image and its mip pyramid.

/// A mip pyramid of a source image: level 0 is the image, each next level halves both sides
/// (rounding up) with a 2x2 box filter (downsample.h), down to 1x1. Built once per source,
/// reused per frame. As a Source, fetch() of a region inside a level is a view into the level,
/// without a copy.
class MipPyramid : public Source {
 public:
  /// Throws InvalidInput for an empty image, channels outside [1, 4] or a pixel buffer of the
  /// wrong size.
  explicit MipPyramid(const Image& source);
  /// Level `i`, in [0, levels()) (not checked): level_width(i) x level_height(i) pixels, the
  /// source image's channels.
  const Image& level(int i) const { return levels_[size_t(i)]; }

  /// Trilinear sample at source-pixel coordinates (x, y) of level 0 (pixel centres at +0.5),
  /// at level-of-detail `lod` (0 = full resolution; clamped to the pyramid), clamp-to-edge.
  /// Writes channels() values in [0, 255] to `out`.
  void sample(double x, double y, double lod, float* out) const;

 private:
  TexelRegion fetch_inside(int level, int x, int y, int width, int height) const override;

  std::vector<Image> levels_;
};

// A source too large for memory: square tiles per level from a provider, held in an LRU cache
// with a byte budget.

/// Which tile a TileProvider is asked for, and the shape it must have.
struct TileRequest {
  int level = 0;  ///< level of detail, 0 = full resolution
  ///@{
  int tile_x = 0, tile_y = 0;  ///< tile indices in the level
  ///@}
  ///@{
  int x = 0, y = 0;  ///< level texel indices of its first texel: tile_x * tile_size, ...
  ///@}
  ///@{
  int width = 0, height = 0;  ///< texels: tile_size, fewer in the level's last column / row
  ///@}
  int channels = 0;  ///< the source's
};

/// Supplies the texels of one tile: an Image of exactly request.width x request.height texels
/// with request.channels channels, texel (i, j) being texel (x + i, y + j) of the level. Called
/// from several threads at once (so it must be thread-safe) and at most once per tile while
/// the tile stays cached; it may throw, and the exception reaches the caller of fetch (render).
using TileProvider = std::function<Image(const TileRequest&)>;

/// How a TiledSource cuts its levels into tiles, how many bytes of them it keeps, and where its
/// coarser levels come from.
struct TiledSourceOptions {
  int tile_size = 256;                     ///< texels per tile side; even, in [2, 16384]
  size_t cache_bytes = size_t(256) << 20;  ///< budget of the tile cache; >= one full tile's bytes
  /// false: the provider supplies every level. true: it is asked for level 0 only; a tile of
  /// level l > 0 is made from the (up to) 4 tiles of level l - 1 it covers by downsample()
  /// (fetched through the cache), so the levels are exactly a MipPyramid's. Then a coarse tile
  /// costs all the level-0 tiles under it the first time (for the top level of a 32768 x 32768
  /// source, the whole image) and nothing while it stays cached: give a budget that holds the
  /// coarse levels, or a provider of every level.
  bool downsample_levels = false;
};

/// What the tile cache holds and has done.
struct TileCacheStats {
  size_t bytes = 0;       ///< texel bytes of the tiles cached now, <= the budget
  size_t peak_bytes = 0;  ///< the most it has held
  size_t tiles_made = 0;  ///< tiles asked of the provider or downsampled, misses included
};

/// A Source whose texels come in tile_size x tile_size tiles per level (fewer texels in a
/// level's last column and row of tiles), made on demand by a TileProvider and kept in a
/// least-recently-used cache that never holds more than cache_bytes of texels. fetch()
/// assembles a region from the tiles it overlaps: a region within one tile is a view into the
/// tile (the region keeps it alive after eviction), a larger one a copy. Memory in use is the
/// cache, plus the regions being read (the renderer's: about one screen block per worker
/// thread), plus the tiles being made. Thread-safe: concurrent fetches share the cache, and a
/// tile two threads miss at once is made once.
class TiledSource : public Source {
 public:
  /// `width` x `height` texels at level 0, `channels` in [1, 4]. Throws InvalidInput naming
  /// "TiledSource" for an empty extent, channels outside [1, 4], an empty provider, an odd or
  /// out-of-range tile size or a budget below one tile; fetch() throws it when the provider
  /// returns a tile of the wrong shape.
  TiledSource(int width, int height, int channels, TileProvider provider,
              const TiledSourceOptions& options = {});
  ~TiledSource() override;

  int tile_size() const { return options_.tile_size; }          ///< texels per tile side
  size_t cache_budget() const { return options_.cache_bytes; }  ///< texel bytes cached at most
  /// What the cache holds now and has made so far; safe to call while other threads fetch.
  TileCacheStats cache_stats() const;

 private:
  struct Cache;

  TexelRegion fetch_inside(int level, int x, int y, int width, int height) const override;
  /// Tile (tile_x, tile_y) of `level`, from the cache or made and cached.
  std::shared_ptr<const Image> tile(int level, int tile_x, int tile_y) const;
  Image make_tile(int level, int tile_x, int tile_y) const;

  TileProvider provider_;
  TiledSourceOptions options_;
  std::unique_ptr<Cache> cache_;
};

}  // namespace geolens
