// Rendering from a 32768 x 32768 tiled source (procedural tiles, an LRU cache), cold and warm;
// a lens dragged over a folder of XYZ tiles whose deepest zoom is 32768 px wide.

#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "core/thread_pool.h"
#include "geolens/geometry/grid.h"
#include "geolens/io/image.h"
#include "geolens/lens/lens_session.h"
#include "geolens/lens/lens_spec.h"
#include "geolens/render/render.h"
#include "geolens/source/source.h"
#include "geolens/source/source_file.h"
#include "geolens/warp/warp_mesh.h"

namespace {

namespace fs = std::filesystem;

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

constexpr int kDeepestZoom = 7;  // 256 px tiles: 32768 px
constexpr int kDistinctTiles = 8;

/// A folder of XYZ tiles, zooms 0 - kDeepestZoom of 256 px (21 845 files), made once in a
/// temporary folder and removed at exit. Each zoom has kDistinctTiles distinct PNGs (procedural
/// texels of that level) and its other tiles are hard links to them: every tile the reader
/// decodes is a real PNG file, without encoding 21 845 of them.
class TileFolder {
 public:
  TileFolder()
      : path_(fs::temp_directory_path() / ("geolens_bench_tiles_" + std::to_string(::getpid()))) {
    for (int z = 0; z <= kDeepestZoom; ++z) {
      const int n = 1 << z;
      for (int x = 0; x < n; ++x) {
        const fs::path column = path_ / std::to_string(z) / std::to_string(x);
        fs::create_directories(column);
        for (int y = 0; y < n; ++y) {
          const fs::path tile = column / (std::to_string(y) + ".png");
          const int index = x * n + y;
          if (index < kDistinctTiles) {
            geolens::TileRequest r;
            r.level = kDeepestZoom - z;
            r.tile_x = x;
            r.tile_y = y;
            r.x = x * 256;
            r.y = y * 256;
            r.width = r.height = 256;
            r.channels = 3;
            geolens::save_image(tile.string(), procedural_tile(r));
            continue;
          }
          const int distinct = (x + 3 * y) % std::min(kDistinctTiles, n * n);
          const fs::path target = path_ / std::to_string(z) / std::to_string(distinct / n) /
                                  (std::to_string(distinct % n) + ".png");
          std::error_code error;
          fs::create_hard_link(target, tile, error);
          if (error) fs::copy_file(target, tile);
        }
      }
    }
  }
  ~TileFolder() {
    std::error_code error;
    fs::remove_all(path_, error);
  }
  std::string path() const { return path_.string(); }

 private:
  fs::path path_;
};

/// Resident set size now, MB (/proc/self/statm).
double rss_mb() {
  long pages = 0, resident = 0;
  std::ifstream("/proc/self/statm") >> pages >> resident;
  return double(resident) * double(::sysconf(_SC_PAGESIZE)) / 1e6;
}

/// The process's peak resident set size so far, MB (getrusage: ru_maxrss, KiB on Linux).
double max_rss_mb() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) * 1024 / 1e6;
}

/// The counter `name` of `file`.
double counter(const geolens::SourceFile& file, const std::string& name) {
  for (const auto& [key, value] : file.counters())
    if (key == name) return value;
  return 0;
}

constexpr int kPassFrames = 60;  // frames of one pass across the frame
constexpr int kPasses = 3;

/// A zoom-8 circle lens (r = 100 frame px, focus model defaults, LensSession drafts as
/// LensWorker solves a drag) dragged over the 4096 px frame of the tile folder (zoom 4, scale 8:
/// the focus is drawn from zoom 7, 32768 px wide) in kPasses passes of kPassFrames steps, one
/// frame per iteration: left to right at a quarter of the height, back at half, across again at
/// three quarters, each pass reading a new strip of zoom 7, together more than twice what the
/// cache holds. Each frame: the lens solved and the whole frame rendered at 4096 x 4096 (what
/// `geolens magnify FOLDER --size 4096x4096` writes) through the folder's LRU cache (256 MiB,
/// open_source's), on a pool of 2 threads kept across frames. Counters: tiles decoded per frame
/// and at most in one (the first, cold); the texel bytes of all the drag's tiles (what an
/// unbounded cache would hold) and the cache's peak; the resident set before the drag, at the end
/// of each pass (the frame's output still held) and the process's peak.
void BM_TileDrag(benchmark::State& state) {
  static const TileFolder folder;
  geolens::SourceFileOptions open_options;
  open_options.width = open_options.height = 4096;
  const geolens::SourceFile file = geolens::open_source(folder.path(), open_options);
  const int side = file.frame_width;
  geolens::LensSession session(side, side);
  geolens::ThreadPool pool(2);
  geolens::RenderOptions options;
  options.width = options.height = side;
  options.pool = &pool;
  const double rss_before = rss_mb(), read_before = counter(file, "tiles_read");
  double most_read = 0, rss_pass[kPasses] = {};
  int frame = 0;
  for (auto _ : state) {
    const int pass = frame / kPassFrames % kPasses, step = frame % kPassFrames;
    const double t = double(pass % 2 == 0 ? step : kPassFrames - 1 - step) / (kPassFrames - 1);
    const std::string spec = "circle:" + std::to_string(128 + (side - 256) * t) + "," +
                             std::to_string(side * (pass + 1) / (kPasses + 1)) + ",100:8";
    const double read = counter(file, "tiles_read");
    const geolens::LensResult result = session.update(
        geolens::parse_lens_spec(spec, 8, geolens::Profile::kGaussian, 0, side, side), {}, true);
    const geolens::Image out = geolens::render(result.warp, file, options);
    benchmark::DoNotOptimize(out.pixels.data());
    most_read = std::max(most_read, counter(file, "tiles_read") - read);
    if (++frame % kPassFrames == 0) rss_pass[pass] = rss_mb();
  }
  const double read = counter(file, "tiles_read") - read_before;
  state.counters["tiles_read_per_frame"] = read / frame;
  state.counters["tiles_read_max_frame"] = most_read;
  state.counters["tiles_read_MB"] = read * 256 * 256 * 3 / 1e6;
  state.counters["peak_cache_MB"] =
      double(dynamic_cast<const geolens::TiledSource&>(*file.source).cache_stats().peak_bytes) /
      1e6;
  state.counters["missing_tiles"] = counter(file, "missing_tiles");
  state.counters["rss_before_MB"] = rss_before;
  for (int pass = 0; pass < kPasses; ++pass)
    state.counters["rss_pass" + std::to_string(pass + 1) + "_MB"] = rss_pass[pass];
  state.counters["max_rss_MB"] = max_rss_mb();
}
BENCHMARK(BM_TileDrag)
    ->Iterations(kPasses* kPassFrames)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
