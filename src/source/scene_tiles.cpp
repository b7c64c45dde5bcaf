#include "source/scene_tiles.h"

#include <atomic>
#include <chrono>
#include <cmath>

#include "geolens/core/errors.h"

namespace geolens {

PixelRegion tile_region(const TileRequest& request, int detail_levels) {
  PixelRegion region;
  region.pixel_size = std::ldexp(1.0, request.level - detail_levels);
  region.x = request.x;
  region.y = request.y;
  region.width = request.width;
  region.height = request.height;
  return region;
}

SourceFile scene_source(RegionRenderer render, int frame_width, int frame_height, int detail_levels,
                        const TiledSourceOptions& tiling, const std::string& kind) {
  const char* f = "scene_source";
  require(frame_width >= 1 && frame_height >= 1, f,
          "the frame " + std::to_string(frame_width) + " x " + std::to_string(frame_height) +
              " is empty");
  require(detail_levels >= 0 && detail_levels <= 4, f,
          "detail levels " + std::to_string(detail_levels) + " is not in [0, 4]");
  const long long width = (long long)(frame_width) << detail_levels;
  const long long height = (long long)(frame_height) << detail_levels;
  require(width <= (1 << 20) && height <= (1 << 20), f,
          "level 0 would be " + std::to_string(width) + " x " + std::to_string(height) +
              " texels, more than 2^20 a side");
  require(bool(render), f, "no renderer");
  struct Tally {
    std::atomic<long long> nanoseconds{0};
  };
  auto tally = std::make_shared<Tally>();
  TileProvider provider = [render, detail_levels, tally](const TileRequest& request) {
    const auto start = std::chrono::steady_clock::now();
    Image tile = render(tile_region(request, detail_levels));
    tally->nanoseconds += std::chrono::duration_cast<std::chrono::nanoseconds>(
                              std::chrono::steady_clock::now() - start)
                              .count();
    return tile;
  };
  auto source = std::make_shared<TiledSource>(int(width), int(height), 3, provider, tiling);
  SourceFile file;
  file.source = source;
  file.frame_width = frame_width;
  file.frame_height = frame_height;
  file.scale = std::ldexp(1.0, detail_levels);
  file.kind = kind;
  file.counters = [source, tally]() -> std::vector<std::pair<std::string, double>> {
    return {{"tiles_rendered", double(source->cache_stats().tiles_made)},
            {"tile_render_seconds", double(tally->nanoseconds.load()) * 1e-9}};
  };
  return file;
}

}  // namespace geolens
