// 3D sources on the CPU: a 1024 x 1024 view of a 70k-triangle mesh and of a 256^3 volume, and
// the extra cost of re-rendering a zoom-3 focus when the lens moves (its fine tiles, cold).

#include <benchmark/benchmark.h>

#include <cmath>

#include "core/thread_pool.h"
#include "render3d/mesh_renderer.h"
#include "render3d/volume_renderer.h"
#include "source/mesh_source.h"
#include "source/volume_source.h"

namespace {

constexpr int kSide = 1024;

/// A latitude-longitude sphere with a rippled radius: rows x cols quads, 2 rows cols triangles
/// (186 x 186: 69 192).
geolens::TriangleMesh rippled_sphere(int rows, int cols) {
  geolens::TriangleMesh mesh;
  mesh.V.resize((rows + 1) * cols, 3);
  for (int i = 0; i <= rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const double theta = M_PI * i / rows, phi = 2 * M_PI * j / cols;
      const double r = 1 + 0.05 * std::sin(8 * theta) * std::cos(6 * phi);
      mesh.V.row(i * cols + j) << r * std::sin(theta) * std::cos(phi), r * std::cos(theta),
          r * std::sin(theta) * std::sin(phi);
    }
  mesh.F.resize(2 * rows * cols, 3);
  int t = 0;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const int a = i * cols + j, b = i * cols + (j + 1) % cols, c = a + cols, d = b + cols;
      mesh.F.row(t++) << a, b, c;
      mesh.F.row(t++) << b, d, c;
    }
  return mesh;
}

/// A 256^3 CT-like phantom (Hounsfield units): a skull (a bone shell), soft tissue inside, and
/// a denser ball off centre, in air.
geolens::ScalarVolume head_phantom() {
  geolens::ScalarVolume v;
  v.nx = v.ny = v.nz = 256;
  v.values.resize(size_t(256) * 256 * 256);
  size_t n = 0;
  for (int k = 0; k < 256; ++k)
    for (int j = 0; j < 256; ++j)
      for (int i = 0; i < 256; ++i) {
        const double r = std::sqrt((i - 127.5) * (i - 127.5) + (j - 127.5) * (j - 127.5) +
                                   (k - 127.5) * (k - 127.5) * 1.3);
        const double ball = std::sqrt((i - 160.0) * (i - 160.0) + (j - 110.0) * (j - 110.0) +
                                      (k - 140.0) * (k - 140.0));
        float value = -1000;
        if (r < 110) value = 40;
        if (r >= 100 && r < 110) value = 900;
        if (ball < 20) value = 600;
        v.values[n++] = value;
      }
  return v;
}

void BM_MeshView(benchmark::State& state) {
  geolens::MeshStyle style;
  style.samples = int(state.range(0));
  const geolens::MeshRenderer renderer(rippled_sphere(186, 186), {}, kSide, kSide, style);
  geolens::ThreadPool pool(2);
  for (auto _ : state)
    benchmark::DoNotOptimize(renderer.render({1, 0, 0, kSide, kSide}, &pool).pixels.data());
  state.counters["triangles"] = double(renderer.triangles());
}
BENCHMARK(BM_MeshView)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_VolumeView(benchmark::State& state) {
  geolens::VolumeStyle style;
  style.step = double(state.range(0)) / 4;
  const geolens::ScalarVolume volume = head_phantom();
  const geolens::VolumeRenderer renderer(volume, geolens::transfer_preset("ct", volume),
                                         geolens::VolumeSourceOptions{}.camera, kSide, kSide,
                                         style);
  geolens::ThreadPool pool(2);
  for (auto _ : state)
    benchmark::DoNotOptimize(renderer.render({1, 0, 0, kSide, kSide}, &pool).pixels.data());
}
BENCHMARK(BM_VolumeView)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond)->UseRealTime();

/// A lens moved to a new place needs the level-0 tiles (4x) under its focus: a 200 x 200 frame
/// pixel focus is 800 x 800 texels (here 16 tiles of 256), all cold (the worst case: a jump;
/// a drag reuses most of them). Argument: 0 = mesh, 1 = volume. Two threads fetch.
void BM_FocusTiles(benchmark::State& state) {
  geolens::ThreadPool pool(2);
  const geolens::ScalarVolume volume =
      state.range(0) == 1 ? head_phantom() : geolens::ScalarVolume{};
  for (auto _ : state) {
    state.PauseTiming();
    const geolens::SourceFile file =
        state.range(0) == 0
            ? geolens::mesh_source(rippled_sphere(186, 186), kSide, kSide)
            : geolens::volume_source(volume, geolens::transfer_preset("ct", volume), kSide, kSide);
    state.ResumeTiming();
    // 4 x 4 blocks of 200 x 200 texels, fetched on the two threads.
    pool.run(16, [&](size_t b) {
      const int x = 1600 + int(b % 4) * 200, y = 1600 + int(b / 4) * 200;
      benchmark::DoNotOptimize(file.source->fetch(0, x, y, 200, 200).data);
    });
  }
}
BENCHMARK(BM_FocusTiles)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
