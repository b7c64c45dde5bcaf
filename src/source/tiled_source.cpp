#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <exception>
#include <future>
#include <mutex>
#include <shared_mutex>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/source/source.h"
#include "source/downsample.h"

namespace geolens {

namespace {

struct TileKey {
  int level, x, y;
  bool operator==(const TileKey& o) const { return level == o.level && x == o.x && y == o.y; }
};

struct TileKeyHash {
  size_t operator()(const TileKey& k) const {
    return size_t(k.level) * 0x9E3779B97F4A7C15ull ^ size_t(uint32_t(k.x)) * 0xC2B2AE3D27D4EB4Full ^
           size_t(uint32_t(k.y)) * 0x165667B19E3779F9ull;
  }
};

using TilePtr = std::shared_ptr<const Image>;

/// Copies the texels of `tile` (whose first texel is level texel (tile_x0, tile_y0)) that lie in
/// [x, x + width) x [y, y + height) to `out`, the region's buffer (row stride `stride` bytes).
void copy_overlap(const Image& tile, int tile_x0, int tile_y0, int x, int y, int width, int height,
                  uint8_t* out, size_t stride) {
  const int x0 = std::max(x, tile_x0), x1 = std::min(x + width, tile_x0 + tile.width);
  const int y0 = std::max(y, tile_y0), y1 = std::min(y + height, tile_y0 + tile.height);
  const size_t bytes = size_t(x1 - x0) * size_t(tile.channels);
  for (int row = y0; row < y1; ++row)
    std::memcpy(out + size_t(row - y) * stride + size_t(x0 - x) * size_t(tile.channels),
                tile.at(x0 - tile_x0, row - tile_y0), bytes);
}

}  // namespace

struct TiledSource::Cache {
  struct Entry {
    TilePtr tile;
    std::atomic<uint64_t> last_used;  ///< a tick of `clock`; written under the shared lock
  };
  /// Shared for a hit (the renderer's threads read the cache at once), exclusive to change it.
  std::shared_mutex mutex;
  std::unordered_map<TileKey, Entry, TileKeyHash> tiles;
  std::unordered_map<TileKey, std::shared_future<TilePtr>, TileKeyHash> being_made;
  std::atomic<uint64_t> clock{0};
  TileCacheStats stats;

  /// The cached tile, marked as just used, or null.
  TilePtr find(const TileKey& key) {
    const auto hit = tiles.find(key);
    if (hit == tiles.end()) return nullptr;
    hit->second.last_used.store(++clock, std::memory_order_relaxed);
    return hit->second.tile;
  }

  /// Caches `tile`, first evicting the least recently used tiles until it fits the budget.
  void insert(const TileKey& key, const TilePtr& tile, size_t budget) {
    const size_t bytes = tile->pixels.size();
    while (stats.bytes + bytes > budget && !tiles.empty()) {
      auto oldest = tiles.begin();
      for (auto it = tiles.begin(); it != tiles.end(); ++it)
        if (it->second.last_used.load(std::memory_order_relaxed) <
            oldest->second.last_used.load(std::memory_order_relaxed))
          oldest = it;
      stats.bytes -= oldest->second.tile->pixels.size();
      tiles.erase(oldest);
    }
    Entry& entry = tiles[key];
    entry.tile = tile;
    entry.last_used.store(++clock, std::memory_order_relaxed);
    stats.bytes += bytes;
    stats.peak_bytes = std::max(stats.peak_bytes, stats.bytes);
  }
};

TiledSource::TiledSource(int width, int height, int channels, TileProvider provider,
                         const TiledSourceOptions& options)
    : Source(width, height, channels, "TiledSource"),
      provider_(std::move(provider)),
      options_(options),
      cache_(std::make_unique<Cache>()) {
  const char* fn = "TiledSource";
  require(bool(provider_), fn, "the tile provider is empty");
  require(options.tile_size >= 2 && options.tile_size <= 16384 && options.tile_size % 2 == 0, fn,
          "tile_size must be even and in [2, 16384], got " + std::to_string(options.tile_size));
  const size_t tile_bytes =
      size_t(options.tile_size) * size_t(options.tile_size) * size_t(channels);
  require(options.cache_bytes >= tile_bytes, fn,
          "cache_bytes must hold a tile (" + std::to_string(tile_bytes) + " bytes), got " +
              std::to_string(options.cache_bytes));
}

TiledSource::~TiledSource() = default;

TileCacheStats TiledSource::cache_stats() const {
  std::shared_lock<std::shared_mutex> lock(cache_->mutex);
  return cache_->stats;
}

Image TiledSource::make_tile(int level, int tile_x, int tile_y) const {
  const int size = options_.tile_size;
  TileRequest request;
  request.level = level;
  request.tile_x = tile_x;
  request.tile_y = tile_y;
  request.x = tile_x * size;
  request.y = tile_y * size;
  request.width = std::min(size, level_width(level) - request.x);
  request.height = std::min(size, level_height(level) - request.y);
  request.channels = channels();
  if (level > 0 && options_.downsample_levels) {
    // The finer texels [2x, 2x + 2 width) x [2y, 2y + 2 height), clipped to level - 1, are tiles
    // 2 tile_x, 2 tile_x + 1 by 2 tile_y, 2 tile_y + 1 where they exist; the origin is even, so
    // downsample() rounds as for the whole level.
    const int fine_x = 2 * request.x, fine_y = 2 * request.y;
    const int fine_w = std::min(2 * size, level_width(level - 1) - fine_x);
    const int fine_h = std::min(2 * size, level_height(level - 1) - fine_y);
    Image fine(fine_w, fine_h, channels());
    const size_t stride = size_t(fine_w) * size_t(channels());
    for (int j = 0; j < 2 && fine_y + j * size < fine_y + fine_h; ++j)
      for (int i = 0; i < 2 && fine_x + i * size < fine_x + fine_w; ++i) {
        const TilePtr part = tile(level - 1, 2 * tile_x + i, 2 * tile_y + j);
        copy_overlap(*part, fine_x + i * size, fine_y + j * size, fine_x, fine_y, fine_w, fine_h,
                     fine.pixels.data(), stride);
      }
    return downsample(fine);
  }
  Image made = provider_(request);
  require(
      made.width == request.width && made.height == request.height &&
          made.channels == request.channels &&
          made.pixels.size() == size_t(made.width) * size_t(made.height) * size_t(made.channels),
      "TiledSource",
      "the provider returned a " + std::to_string(made.width) + " x " +
          std::to_string(made.height) + " x " + std::to_string(made.channels) + " tile (" +
          std::to_string(made.pixels.size()) + " bytes) for tile (" + std::to_string(tile_x) +
          ", " + std::to_string(tile_y) + ") of level " + std::to_string(level) + ", expected " +
          std::to_string(request.width) + " x " + std::to_string(request.height) + " x " +
          std::to_string(request.channels));
  return made;
}

std::shared_ptr<const Image> TiledSource::tile(int level, int tile_x, int tile_y) const {
  Cache& cache = *cache_;
  const TileKey key{level, tile_x, tile_y};
  {
    std::shared_lock<std::shared_mutex> lock(cache.mutex);
    if (TilePtr hit = cache.find(key)) return hit;
  }
  std::unique_lock<std::shared_mutex> lock(cache.mutex);
  if (TilePtr hit = cache.find(key)) return hit;  // made since
  if (const auto pending = cache.being_made.find(key); pending != cache.being_made.end()) {
    const std::shared_future<TilePtr> made = pending->second;
    lock.unlock();
    return made.get();  // rethrows the maker's exception
  }
  // Made here, outside the lock; other threads asking for it meanwhile wait for `promise`.
  std::promise<TilePtr> promise;
  cache.being_made.emplace(key, promise.get_future().share());
  ++cache.stats.tiles_made;
  lock.unlock();
  TilePtr made;
  try {
    made = std::make_shared<const Image>(make_tile(level, tile_x, tile_y));
  } catch (...) {
    lock.lock();
    cache.being_made.erase(key);
    lock.unlock();
    promise.set_exception(std::current_exception());
    throw;
  }
  lock.lock();
  cache.being_made.erase(key);
  cache.insert(key, made, options_.cache_bytes);
  lock.unlock();
  promise.set_value(made);
  return made;
}

TexelRegion TiledSource::fetch_inside(int level, int x, int y, int width, int height) const {
  const int size = options_.tile_size;
  const int tx0 = x / size, tx1 = (x + width - 1) / size;
  const int ty0 = y / size, ty1 = (y + height - 1) / size;
  TexelRegion region;
  region.x = x;
  region.y = y;
  region.width = width;
  region.height = height;
  region.channels = channels();
  if (tx0 == tx1 && ty0 == ty1) {  // a view into the tile
    TilePtr only = tile(level, tx0, ty0);
    region.data = only->at(x - tx0 * size, y - ty0 * size);
    region.stride = size_t(only->width) * size_t(channels());
    region.owner = std::move(only);
    return region;
  }
  region.stride = size_t(width) * size_t(channels());
  auto copy = std::make_shared<std::vector<uint8_t>>(region.stride * size_t(height));
  for (int ty = ty0; ty <= ty1; ++ty)
    for (int tx = tx0; tx <= tx1; ++tx)
      copy_overlap(*tile(level, tx, ty), tx * size, ty * size, x, y, width, height, copy->data(),
                   region.stride);
  region.data = copy->data();
  region.owner = std::move(copy);
  return region;
}

}  // namespace geolens
