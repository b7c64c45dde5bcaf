#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <vector>

#include "eval/fixed_text.h"
#include "geolens/core/errors.h"
#include "geolens/eval/comparison.h"
#include "geolens/render/annotate.h"
#include "geolens/render/overlay.h"

namespace geolens {

namespace {

// `warp` with its screen translated and scaled so that the square window at `origin` with side
// `side` (screen pixels) fills a tile x tile picture.
WarpMesh framed(const WarpMesh& warp, const Eigen::Vector2d& origin, double side, int tile) {
  WarpMesh out = warp;
  out.screen = (warp.screen.rowwise() - origin.transpose()) * (tile / side);
  out.screen_width = out.screen_height = tile;
  return out;
}

// The closed loop `loop` (source pixels) in the tile's pixels (x = (p - origin) scale) as dashes
// `dash` tile pixels long, as far apart, each a LineString.
VectorData dashes(const std::vector<Eigen::Vector2d>& loop, const Eigen::Vector2d& origin,
                  double scale, double dash) {
  VectorData data;
  std::vector<Eigen::Vector2d> current;
  auto finish = [&] {
    if (current.size() >= 2) {
      Geometry line{GeometryType::kLineString, {Eigen::MatrixX2d(current.size(), 2)}, {}, {}};
      for (size_t i = 0; i < current.size(); ++i) line.paths[0].row(Eigen::Index(i)) = current[i];
      data.features.push_back({line, "", "null"});
    }
    current.clear();
  };
  bool on = true;
  double left = dash;  // tile pixels to the end of this dash or gap
  for (size_t i = 0; i < loop.size(); ++i) {
    const Eigen::Vector2d a = (loop[i] - origin) * scale;
    const Eigen::Vector2d b = (loop[(i + 1) % loop.size()] - origin) * scale;
    const double length = (b - a).norm();
    for (double t = 0; t < length;) {
      const double step = std::min(length - t, left);
      if (on) {
        if (current.empty()) current.push_back(a + (b - a) * (t / length));
        current.push_back(a + (b - a) * ((t + step) / length));
      }
      t += step;
      left -= step;
      if (left > 1e-9) continue;
      if (on) finish();
      on = !on;
      left = dash;
    }
  }
  finish();
  return data;
}

}  // namespace

void require_panel_tile(int tile, const char* function) {
  require(tile >= 64 && tile <= 1024, function,
          "must be in [64, 1024], got " + std::to_string(tile));
}

Image comparison_output(const Comparison& comparison, const ComparedMethod& method,
                        const SourceFile& source) {
  RenderOptions options;
  options.width = comparison.width;
  options.height = comparison.height;
  return to_rgb(render(method.warp, source, options));
}

Image comparison_heatmap(const ComparedMethod& method, const Image& output, double heat_max) {
  return with_legend(
      heatmap(method.warp, method.measures.conformal, method.measures.flipped, output, heat_max),
      heat_max, method.name + ": shape distortion s1/s2 - 1");
}

Image comparison_panel(const Comparison& comparison, const SourceFile& source, double heat_max,
                       int tile) {
  require_panel_tile(tile, "comparison_panel");
  const std::vector<ComparedMethod>& methods = comparison.methods;
  Eigen::AlignedBox2d box;
  for (const CircleLens& lens : comparison.targets) {
    box.extend(lens.center - Eigen::Vector2d::Constant(lens.radius));
    box.extend(lens.center + Eigen::Vector2d::Constant(lens.radius));
  }
  const double side = 1.3 * box.sizes().maxCoeff();
  const Eigen::Vector2d origin = box.center() - Eigen::Vector2d::Constant(side / 2);
  // Labels at twice the font size when the longest method name (158 pixels) fits the tile.
  const int scale = tile >= 176 ? 2 : 1, line = 11 * scale, gap = 6;
  const int label_height = 4 * line + gap, cell_width = tile + gap,
            cell_height = label_height + 2 * tile + gap + 2 * gap;
  const int columns = 4, rows = int(methods.size() + 1 + columns - 1) / columns;
  Image panel(columns * cell_width + gap, rows * cell_height + gap, 3, 255);
  RenderOptions options;
  options.width = options.height = tile;
  const std::array<uint8_t, 3> ink = {20, 20, 20};

  const WarpMesh identity = identity_warp(comparison.width, comparison.height);
  Image input = to_rgb(render(framed(identity, origin, side, tile), source, options));
  // The regions given, and dashed, the footprints.
  std::vector<Region> regions;
  for (const Lens& lens : comparison.lenses) regions.push_back(lens.region);
  outline_regions(input, regions, origin, tile / side, tile / side);
  OverlayStyle dashed;
  dashed.line_colour = {220, 30, 30};
  dashed.line_width = 1.5;
  for (const std::vector<Eigen::Vector2d>& footprint : comparison.footprints)
    draw_overlay(input, dashes(footprint, origin, tile / side, 6), dashed);

  for (size_t cell = 0; cell <= methods.size(); ++cell) {
    const int left = gap + int(cell % columns) * cell_width;
    const int top = gap + int(cell / columns) * cell_height;
    if (cell == 0) {
      draw_text(panel, left, top, "input", scale, ink);
      draw_text(panel, left, top + line, "footprint dashed", scale, ink);
      paste(panel, input, left, top + label_height);
      // The notes go where the heatmap is in the other cells, in the largest font that fits.
      const char* notes[] = {"top: output",  "below: shape", "distortion",    "s1/s2 - 1",
                             "focus: inner", "half of lens", "hides: % image"};
      const int count = int(std::size(notes));
      const int note_scale = count * (11 * scale + 2) <= tile ? scale : 1;
      if (count * (11 * note_scale + 2) > tile) continue;
      int y = top + label_height + tile + gap;
      for (const char* note : notes) {
        draw_text(panel, left, y, note, note_scale, ink);
        y += 11 * note_scale + 2;
      }
      continue;
    }
    const ComparedMethod& m = methods[cell - 1];
    draw_text(panel, left, top, m.name, scale, ink);
    draw_text(panel, left, top + line, "zoom " + fixed_text(m.zoom_measured.front(), 2), scale,
              ink);
    draw_text(panel, left, top + 2 * line, "max " + fixed_text(m.regions.overall.conformal_max, 2),
              scale, ink);
    std::string notes;
    if (m.regions.occluded_percent >= 0.05)
      notes = "hides " + fixed_text(m.regions.occluded_percent, 1) + "%";
    if (m.regions.overall.flipped > 0)
      notes += (notes.empty() ? "" : ", ") + std::to_string(m.regions.overall.flipped) + " flipped";
    draw_text(panel, left, top + 3 * line, notes, scale, ink);
    const WarpMesh warp = framed(m.warp, origin, side, tile);
    const Image image = to_rgb(render(warp, source, options));
    paste(panel, image, left, top + label_height);
    paste(panel, heatmap(warp, m.measures.conformal, m.measures.flipped, image, heat_max), left,
          top + label_height + tile + gap);
  }
  return with_legend(panel, heat_max, "shape distortion s1/s2 - 1");
}

}  // namespace geolens
