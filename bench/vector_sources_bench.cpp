// Sources drawn per tile on demand (issue 16): an SVG text page through librsvg and a vector map
// through cairo, cold (every tile drawn in the timed render) on 1 and 2 render threads.

#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "geolens/io/geojson.h"
#include "geolens/render/render.h"
#include "geolens/warp/warp_mesh.h"
#include "source/svg_source.h"
#include "source/vector_map.h"

namespace {

/// A letter-size page (612 x 792 pt) of 60 lines of 10 pt text and a few strokes, written once.
std::string text_page() {
  const std::string path =
      (std::filesystem::temp_directory_path() / "geolens_bench_text_page.svg").string();
  std::ofstream out(path);
  out << R"(<svg xmlns="http://www.w3.org/2000/svg" width="612pt" height="792pt" )"
      << R"(viewBox="0 0 612 792"><g font-family="DejaVu Serif" font-size="10">)";
  for (int i = 0; i < 60; ++i)
    out << "<text x=\"40\" y=\"" << 40 + 12 * i << "\">Line " << i
        << ": the quick brown fox jumps over the lazy dog, focus and context</text>";
  out << R"(</g><circle cx="420" cy="600" r="90" fill="none" stroke="black"/></svg>)";
  return path;
}

/// The frame's centre magnified `zoom` times onto an output of the frame's size.
geolens::WarpMesh centre_zoom(int width, int height, double zoom) {
  geolens::WarpMesh mesh = geolens::identity_warp(width, height);
  mesh.screen = (mesh.screen.rowwise() - Eigen::RowVector2d(width / 2.0, height / 2.0)) * zoom;
  mesh.screen.rowwise() += Eigen::RowVector2d(width / 2.0, height / 2.0);
  return mesh;
}

void render_cold(benchmark::State& state, const std::function<geolens::SourceFile()>& open) {
  double tiles = 0;
  for (auto _ : state) {
    state.PauseTiming();
    const geolens::SourceFile file = open();
    state.ResumeTiming();
    geolens::RenderOptions options;
    options.width = file.frame_width;
    options.height = file.frame_height;
    options.source_scale = file.scale;
    options.threads = int(state.range(0));
    benchmark::DoNotOptimize(geolens::render(centre_zoom(file.frame_width, file.frame_height, 3),
                                             *file.source, options));
    tiles = file.counters().front().second;
  }
  state.counters["tiles"] = tiles;
}

/// A zoom-3 view of a text page framed 1024 px wide: the tiles of levels 1 and 2 it blends,
/// each a whole-document render by librsvg clipped to the tile.
void BM_SvgTextPageZoom3(benchmark::State& state) {
  const std::string path = text_page();
  geolens::SourceFileOptions options;
  options.width = 1024;
  render_cold(state, [&] { return geolens::open_svg(path, options); });
}
BENCHMARK(BM_SvgTextPageZoom3)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

/// A zoom-3 view of a synthetic map framed 1024 px wide: 400 polygons of 64 vertices, 400 lines,
/// 2000 points, in the default style.
void BM_VectorMapZoom3(benchmark::State& state) {
  std::string json = R"({"type": "FeatureCollection", "features": [)";
  auto position = [](double lon, double lat) {
    return "[" + std::to_string(lon) + "," + std::to_string(lat) + "]";
  };
  for (int i = 0; i < 400; ++i) {
    const double lon = -10 + (i % 20) * 2, lat = 35 + (i / 20) * 1.2;
    std::string ring;
    for (int k = 0; k <= 64; ++k) {
      const double a = 2 * 3.14159265358979 * (k % 64) / 64, r = 0.5 + 0.2 * std::sin(5 * a);
      ring += (k ? "," : "") + position(lon + r * std::cos(a), lat + r * std::sin(a));
    }
    json += R"({"type": "Feature", "properties": null, "geometry": {"type": "Polygon", )"
            R"("coordinates": [[)" +
            ring + "]]}},";
    json += R"({"type": "Feature", "properties": null, "geometry": {"type": "LineString", )"
            R"("coordinates": [)" +
            position(lon, lat) + "," + position(lon + 1.5, lat + 0.9) + "]}},";
  }
  for (int i = 0; i < 2000; ++i)
    json += std::string(i ? "," : "") + R"({"type": "Feature", "properties": {"name": "P)" +
            std::to_string(i) + R"(", "scalerank": )" + std::to_string(i % 9) +
            R"(}, "geometry": {"type": "Point", "coordinates": )" +
            position(-10 + std::fmod(i * 0.37, 40), 35 + std::fmod(i * 0.23, 24)) + "}}";
  json += "]}";
  const geolens::VectorData data = geolens::parse_geojson(json, "synthetic");
  const geolens::MapStyle style = geolens::default_map_style();
  render_cold(state, [&] { return geolens::vector_map_source(data, style, 1024); });
}
BENCHMARK(BM_VectorMapZoom3)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
