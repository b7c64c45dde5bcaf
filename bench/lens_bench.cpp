// Stage timings of the geometric lens at the paper's grid sizes (100x100 and 200x200 vertices).

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "geolens/geometry/grid.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens_session.h"
#include "lens/flatten.h"
#include "lens/lift.h"
#include "lens/texture_map.h"

namespace geolens {
namespace {

// The case scaled to the grid: a 1024 px image, r = 150 px at the centre, the bump
// height the calibration finds for zoom 2 with the default options (h0 = 0.76 r).
struct Scene {
  explicit Scene(int mesh) : grid(make_grid(1024, 1024, mesh)) {
    lifted = lift(grid.V, {lens}, {0.76 * 150});
    fixed.resize(grid.sides.size());
    for (size_t i = 0; i < fixed.size(); ++i) fixed[i] = !lifted.inside[i] || grid.sides[i];
  }
  Grid grid;
  Lens lens{Region::circle({512, 512}, 150)};
  Lifted lifted;
  std::vector<char> fixed;
};

void BM_Lift(benchmark::State& state) {
  const Scene s(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(lift(s.grid.V, {s.lens}, {0.76 * 150}));
  state.counters["vertices"] = double(s.grid.V.rows());
}

void BM_Texture(benchmark::State& state) {
  const Scene s(int(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(
        harmonic_texture(s.lifted.V, s.grid.F, s.fixed, s.grid.V, TextureWeights::kCotan));
  state.counters["vertices"] = double(s.grid.V.rows());
}

// Assembling the global matrix and its sparse Cholesky factorization (the paper's
// "pre-processing").
void BM_Factorize(benchmark::State& state) {
  const Scene s(int(state.range(0)));
  for (auto _ : state) {
    const Flattener flattener(s.lifted.V, s.grid.F, s.lifted.level, s.grid.sides, FlattenOptions{});
    flattener.factorize();
  }
  state.counters["vertices"] = double(s.grid.V.rows());
}

// One local/global iteration (the paper's per-iteration figure).
void BM_Iteration(benchmark::State& state) {
  const Scene s(int(state.range(0)));
  FlattenOptions o;
  o.max_iterations = 1;
  const Flattener flattener(s.lifted.V, s.grid.F, s.lifted.level, s.grid.sides, o);
  for (auto _ : state) benchmark::DoNotOptimize(flattener.solve(s.grid.V));
  state.counters["vertices"] = double(s.grid.V.rows());
}

// The whole flattening to the paper's 0.1 % stop, factorization included.
void BM_Flatten(benchmark::State& state) {
  const Scene s(int(state.range(0)));
  int iterations = 0;
  for (auto _ : state) {
    const FlattenResult r = flatten(s.lifted.V, s.grid.F, s.lifted.level, s.grid.sides, {});
    iterations = r.iterations;
  }
  state.counters["iterations"] = iterations;
}

// A full magnify: calibration to zoom 2 (several solves) and everything they contain.
void BM_SolveZoom2(benchmark::State& state) {
  LensOptions o;
  o.model = LensModel::kAuto;  // the lift and field figures of bench/README.md
  o.mesh = int(state.range(0));
  const GeometricLens lens(1024, 1024, o);
  const Lens l{Region::circle({512, 512}, 150)};
  int solves = 0;
  for (auto _ : state) solves = lens.solve({l}).solves;
  state.counters["solves"] = solves;
}

BENCHMARK(BM_Lift)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Texture)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Factorize)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Iteration)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Flatten)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SolveZoom2)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace geolens

namespace geolens {
namespace {

// The interactive path: a zoom-2 lens dragged `step` px per frame from x = 400 to 620 across
// the image centre, then back to 400 in one jump, over and over; each iteration is one update()
// to the 0.1 % tolerance, zoom checked. A fixed 3 x 74 frames, so the mean covers whole drags:
// every window rebuild of the flattening's factorization and every jump back.
// The last argument picks the model: 0 the auto model (the lift for a circle, the field for a
// polygon; the default before issue 13), 1 the focus model (the default since), 2 the focus
// model's drafts (what LensWorker shows while a lens is dragged).
LensModel model_argument(std::int64_t argument) {
  return argument ? LensModel::kFocus : LensModel::kAuto;
}
bool draft_argument(std::int64_t argument) { return argument == 2; }

// The sessions' options: the model and grid given; FlattenOptions::threads from the environment's
// GEOLENS_BENCH_THREADS where set (1: the calling thread only, as the browser's build runs), else
// one thread per hardware thread.
LensOptions session_options(std::int64_t mesh, std::int64_t model) {
  LensOptions o;
  o.model = model_argument(model);
  o.mesh = int(mesh);
  if (const char* threads = std::getenv("GEOLENS_BENCH_THREADS"))
    o.flatten.threads = std::atoi(threads);
  return o;
}

void BM_UpdateMoved(benchmark::State& state) {
  const LensOptions o = session_options(state.range(0), state.range(2));
  const double step = double(state.range(1));
  const bool draft = draft_argument(state.range(2));
  LensSession lens(1024, 1024, o);
  double x = 400;
  lens.update({Lens{Region::circle({x, 512}, 150)}});
  int solves = 0, iterations = 0;
  for (auto _ : state) {
    x = x + step > 620 ? 400 : x + step;
    const LensResult r = lens.update({Lens{Region::circle({x, 512}, 150)}}, {}, draft);
    solves += r.solves;
    iterations += r.flattening.iterations;
  }
  state.counters["solves/update"] = benchmark::Counter(solves, benchmark::Counter::kAvgIterations);
  state.counters["iterations/update"] =
      benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
}

// The same drag with a 5-pointed star of radius 120 px at zoom 2.5. The last argument picks the
// model as above (the auto model takes the field model for a polygon) and how the star moves:
// its Region built anew every frame (rasterized medial axis and distance fields included, about
// 1 ms; 0 to 2), or moved by Region::translated, as geolens-view drags it (3 to 5).
void BM_UpdateMovedStar(benchmark::State& state) {
  const std::int64_t model = state.range(1) % 3;
  const bool translate = state.range(1) >= 3;
  LensSession lens(1024, 1024, session_options(state.range(0), model));
  std::vector<Eigen::Vector2d> outline;
  for (int k = 0; k < 10; ++k) {
    const double r = k % 2 == 0 ? 120 : 0.382 * 120, a = M_PI / 2 + k * M_PI / 5;
    outline.emplace_back(r * std::cos(a), 512 - r * std::sin(a));
  }
  const Region at_zero = Region::polygon(outline);
  auto star = [&](double x) {
    if (translate) return at_zero.translated({x, 0});
    std::vector<Eigen::Vector2d> p = outline;
    for (Eigen::Vector2d& v : p) v.x() += x;
    return Region::polygon(p);
  };
  const bool draft = draft_argument(model);
  double x = 400;
  lens.update({Lens{star(x), 2.5}}, {}, draft);
  int iterations = 0;
  for (auto _ : state) {
    x = x + 3 > 620 ? 400 : x + 3;
    iterations += lens.update({Lens{star(x), 2.5}}, {}, draft).flattening.iterations;
  }
  state.counters["iterations/update"] =
      benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
}

// First placement: a new GeometricLens, nothing cached, calibrated from the first guess.
void BM_UpdateFirst(benchmark::State& state) {
  const LensOptions o = session_options(state.range(0), state.range(1));
  for (auto _ : state) {
    LensSession lens(1024, 1024, o);
    benchmark::DoNotOptimize(lens.update({Lens{Region::circle({512, 512}, 150)}}));
  }
}

BENCHMARK(BM_UpdateMoved)
    ->ArgsProduct({{100, 200}, {3, 10}, {0, 1, 2}})
    ->Iterations(222)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_UpdateMovedStar)
    ->ArgsProduct({{100, 200}, {0, 1, 2, 3, 4, 5}})
    ->Iterations(222)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_UpdateFirst)->ArgsProduct({{100, 200}, {0, 1}})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace geolens

namespace geolens {
namespace {

// Local extent: a r = 200 px zoom-2 lens dragged 3 px per frame on a very large image; the
// argument is the image side. The cost should not depend on it.
void BM_LocalUpdateMoved(benchmark::State& state) {
  const double side = double(state.range(0));
  LensOptions o;
  o.model = LensModel::kAuto;  // the lift and field figures of bench/README.md
  o.extent = Extent::kLocal;
  LensSession lens(side, side, o);
  double x = side / 2;
  lens.update({Lens{Region::circle({x, side / 2}, 200)}});
  for (auto _ : state) {
    x += 3;
    benchmark::DoNotOptimize(lens.update({Lens{Region::circle({x, side / 2}, 200)}}));
  }
}

BENCHMARK(BM_LocalUpdateMoved)->Arg(4096)->Arg(16384)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace geolens
