// Mip pyramid construction and rendering of a 4096 x 4096 source.

#include <benchmark/benchmark.h>

#include "geolens/geometry/grid.h"
#include "geolens/io/image.h"
#include "geolens/render/render.h"
#include "geolens/warp/warp_mesh.h"

namespace {

constexpr int kSourceSide = 4096;
constexpr int kOutputSide = 1024;

/// A 4096 x 4096 RGB test image with detail at every scale, built once.
const geolens::Image& source_image() {
  static const geolens::Image image = [] {
    geolens::Image out(kSourceSide, kSourceSide, 3);
    for (int y = 0; y < kSourceSide; ++y)
      for (int x = 0; x < kSourceSide; ++x) {
        uint8_t* p = out.at(x, y);
        p[0] = uint8_t(x ^ y);
        p[1] = uint8_t((x * y) >> 8);
        p[2] = uint8_t((x + 3 * y) >> 4);
      }
    return out;
  }();
  return image;
}

/// The identity warp of the source as an n x n vertex grid (make_grid's alternating diagonals),
/// framed for a screen of the source's size (rendering smaller minifies it).
geolens::WarpMesh identity_grid(int n, double side) {
  const geolens::Grid grid = geolens::make_grid(side, side, n);
  geolens::WarpMesh mesh;
  mesh.source = mesh.screen = grid.V;
  mesh.F = grid.F;
  mesh.screen_width = mesh.screen_height = int(side);
  return mesh;
}

void BM_BuildPyramid4096(benchmark::State& state) {
  const geolens::Image& source = source_image();
  for (auto _ : state) {
    geolens::MipPyramid pyramid(source);
    benchmark::DoNotOptimize(pyramid.level(pyramid.levels() - 1).pixels.data());
  }
  state.counters["source_MB"] = double(source.pixels.size()) / 1e6;
}
BENCHMARK(BM_BuildPyramid4096)->Unit(benchmark::kMillisecond);

/// Renders a 1024 x 1024 output from the 4096 x 4096 source through a 100 x 100 vertex grid
/// (19602 triangles); the argument is RenderOptions::threads (0 = hardware concurrency).
void BM_Render1024From4096(benchmark::State& state) {
  static const geolens::MipPyramid pyramid(source_image());
  static const geolens::WarpMesh mesh = identity_grid(100, kSourceSide);
  geolens::RenderOptions options;
  options.width = options.height = kOutputSide;
  options.threads = int(state.range(0));
  for (auto _ : state) {
    geolens::Image out = geolens::render(mesh, pyramid, options);
    benchmark::DoNotOptimize(out.pixels.data());
  }
  state.counters["triangles"] = double(mesh.F.rows());
  state.counters["Mpixel/s"] = benchmark::Counter(double(kOutputSide) * kOutputSide / 1e6,
                                                  benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Render1024From4096)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
