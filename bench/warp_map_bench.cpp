// Points mapped through a WarpMesh (warp/warp_map.h): queries per second on one thread, and the
// cost of building the map, at 100 x 100 and 200 x 200 vertices.

#include <benchmark/benchmark.h>

#include <map>
#include <random>

#include "geolens/lens/geometric_lens.h"
#include "geolens/warp/warp_map.h"

namespace geolens {
namespace {

constexpr int kQueries = 1 << 16;

// The bench scene (bench/README.md): a 1024 px image, one circle r = 150 px at the centre,
// zoom 2, default options but the mesh. Solved once per mesh size.
const WarpMesh& scene(int mesh) {
  static std::map<int, WarpMesh> warps;
  auto it = warps.find(mesh);
  if (it == warps.end()) {
    LensOptions options;
    options.mesh = mesh;
    it = warps
             .emplace(mesh, GeometricLens(1024, 1024, options)
                                .solve({Lens{Region::circle({512, 512}, 150), 2.0}})
                                .warp)
             .first;
  }
  return it->second;
}

// kQueries points uniform over the image, seeded.
Eigen::MatrixX2d queries() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1024);
  Eigen::MatrixX2d P(kQueries, 2);
  for (Eigen::Index i = 0; i < kQueries; ++i) P.row(i) << u(rng), u(rng);
  return P;
}

void count(benchmark::State& state, const WarpMesh& warp) {
  state.SetItemsProcessed(state.iterations() * kQueries);
  state.counters["triangles"] = double(warp.F.rows());
}

// One forward() call per point (single-point API), source points over the image.
void BM_WarpMapForward(benchmark::State& state) {
  const WarpMesh& warp = scene(int(state.range(0)));
  const WarpMap map(warp);
  const Eigen::MatrixX2d P = queries();
  for (auto _ : state)
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      benchmark::DoNotOptimize(map.forward(P.row(i).transpose()));
  count(state, warp);
}

// One inverse() call per point, screen points over the image.
void BM_WarpMapInverse(benchmark::State& state) {
  const WarpMesh& warp = scene(int(state.range(0)));
  const WarpMap map(warp);
  const Eigen::MatrixX2d Q = queries();
  for (auto _ : state)
    for (Eigen::Index i = 0; i < Q.rows(); ++i)
      benchmark::DoNotOptimize(map.inverse(Q.row(i).transpose()));
  count(state, warp);
}

// forward_batch() over all the points at once.
void BM_WarpMapForwardBatch(benchmark::State& state) {
  const WarpMesh& warp = scene(int(state.range(0)));
  const WarpMap map(warp);
  const Eigen::MatrixX2d P = queries();
  for (auto _ : state) benchmark::DoNotOptimize(map.forward_batch(P));
  count(state, warp);
}

// Building the map: copying the mesh and indexing both sides.
void BM_WarpMapBuild(benchmark::State& state) {
  const WarpMesh& warp = scene(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(WarpMap(warp));
  state.counters["triangles"] = double(warp.F.rows());
}

BENCHMARK(BM_WarpMapForward)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WarpMapInverse)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WarpMapForwardBatch)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WarpMapBuild)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace geolens
