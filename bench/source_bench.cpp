// Rendering from a 32768 x 32768 tiled source (procedural tiles, an LRU cache), cold and warm.

#include <benchmark/benchmark.h>

#include <cstdint>

#include "geolens/geometry/grid.h"
#include "geolens/io/image.h"
#include "geolens/render/render.h"
#include "geolens/source/tiled_source.h"
#include "geolens/warp/warp_mesh.h"

namespace {

constexpr int kSourceSide = 32768;
constexpr int kOutputSide = 1024;

/// Every level's tiles computed from their coordinates (as a tile server or a file would
/// supply them, without the I/O).
geolens::Image procedural_tile(const geolens::TileRequest& r) {
  geolens::Image tile(r.width, r.height, 3);
  for (int j = 0; j < r.height; ++j) {
    uint8_t* p = tile.at(0, j);
    const int y = r.y + j;
    for (int i = 0; i < r.width; ++i, p += 3) {
      const int x = r.x + i;
      p[0] = uint8_t(x ^ y);
      p[1] = uint8_t((x * y) >> 8);
      p[2] = uint8_t(r.level * 40 + ((x + 3 * y) >> 4));
    }
  }
  return tile;
}

/// An n x n vertex grid (make_grid's alternating diagonals) over the source window at (x0, y0)
/// of side `side` source pixels, framed for a kOutputSide screen.
geolens::WarpMesh window_grid(int n, double x0, double y0, double side) {
  const geolens::Grid grid = geolens::make_grid(side, side, n);
  geolens::WarpMesh mesh;
  mesh.source = grid.V.rowwise() + Eigen::RowVector2d(x0, y0);
  mesh.screen = grid.V * (kOutputSide / side);
  mesh.F = grid.F;
  mesh.screen_width = mesh.screen_height = kOutputSide;
  return mesh;
}

/// Argument 0: the whole source (level 5, 16 tiles); 1: a 1024 x 1024 window at level 0
/// (25 tiles); 2: a 1536 x 1536 window (levels 0 and 1 blended).
geolens::WarpMesh view(int64_t which) {
  if (which == 0) return window_grid(100, 0, 0, kSourceSide);
  if (which == 1) return window_grid(100, 20000.5, 12000.25, 1024);
  return window_grid(100, 20000, 12000, 1536);
}

geolens::TiledSourceOptions cache_options() {
  geolens::TiledSourceOptions options;
  options.tile_size = 256;
  options.cache_bytes = size_t(64) << 20;
  return options;
}

/// A fresh source per iteration: every tile made by the provider, then rendered.
void BM_RenderTiledCold(benchmark::State& state) {
  const geolens::WarpMesh mesh = view(state.range(0));
  geolens::RenderOptions options;
  options.width = options.height = kOutputSide;
  size_t tiles = 0, peak = 0;
  for (auto _ : state) {
    const geolens::TiledSource source(kSourceSide, kSourceSide, 3, procedural_tile,
                                      cache_options());
    geolens::Image out = geolens::render(mesh, source, options);
    benchmark::DoNotOptimize(out.pixels.data());
    tiles = source.cache_stats().tiles_made;
    peak = source.cache_stats().peak_bytes;
  }
  state.counters["peak_cache_MB"] = double(peak) / 1e6;
  state.counters["tiles_made"] = double(tiles);
  state.counters["Mpixel/s"] = benchmark::Counter(double(kOutputSide) * kOutputSide / 1e6,
                                                  benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_RenderTiledCold)
    ->ArgName("view")
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// One source, its cache warmed by a first render: what a frame costs while the view stays.
void BM_RenderTiledWarm(benchmark::State& state) {
  const geolens::WarpMesh mesh = view(state.range(0));
  geolens::RenderOptions options;
  options.width = options.height = kOutputSide;
  const geolens::TiledSource source(kSourceSide, kSourceSide, 3, procedural_tile, cache_options());
  geolens::render(mesh, source, options);
  const size_t warmed = source.cache_stats().tiles_made;
  for (auto _ : state) {
    geolens::Image out = geolens::render(mesh, source, options);
    benchmark::DoNotOptimize(out.pixels.data());
  }
  state.counters["peak_cache_MB"] = double(source.cache_stats().peak_bytes) / 1e6;
  state.counters["tiles_made"] = double(source.cache_stats().tiles_made - warmed);  // 0: all hits
  state.counters["Mpixel/s"] = benchmark::Counter(double(kOutputSide) * kOutputSide / 1e6,
                                                  benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_RenderTiledWarm)
    ->ArgName("view")
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
