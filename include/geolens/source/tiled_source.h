#pragma once
// A source too large for memory: square tiles per level from a provider, held in an LRU cache
// with a byte budget.

#include <cstddef>
#include <functional>
#include <memory>

#include "geolens/io/image.h"
#include "geolens/source/source.h"

namespace geolens {

/// Which tile a TileProvider is asked for, and the shape it must have.
struct TileRequest {
  int level = 0;               ///< level of detail, 0 = full resolution
  int tile_x = 0, tile_y = 0;  ///< tile indices in the level
  int x = 0, y = 0;            ///< level texel indices of its first texel: tile_x * tile_size, ...
  int width = 0, height = 0;   ///< texels: tile_size, fewer in the level's last column / row
  int channels = 0;            ///< the source's
};

/// Supplies the texels of one tile: an Image of exactly request.width x request.height texels
/// with request.channels channels, texel (i, j) being texel (x + i, y + j) of the level. Called
/// from several threads at once (so it must be thread-safe) and at most once per tile while
/// the tile stays cached; it may throw, and the exception reaches the caller of fetch (render).
using TileProvider = std::function<Image(const TileRequest&)>;

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

  int tile_size() const { return options_.tile_size; }
  size_t cache_budget() const { return options_.cache_bytes; }
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
