#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "geolens/core/errors.h"
#include "geolens/eval/comparison.h"
#include "geolens/lens/classic_lens.h"
#include "geolens/measure/distortion.h"
#include "geolens/render/annotate.h"
#include "lens/focus_lens.h"

namespace geolens {

namespace {

SweepPoint measure(const std::string& method, double ratio, const WarpMesh& warp,
                   const Lens& lens) {
  const TriangleDistortion measures = measure_triangles(warp);
  const FocusMeasure focus = measure_foci(warp, measures, {lens}).front();
  return {method,
          ratio,
          focus.zoom,
          focus.uniformity,
          summarize(measures).conformal_max,
          focus.footprint_radius};
}

}  // namespace

std::vector<double> sweep_ratios(double zoom) {
  std::vector<double> ratios = {zoom + 1, 1.5 * zoom, 2 * zoom, 3 * zoom, 4 * zoom};
  std::sort(ratios.begin(), ratios.end());
  ratios.erase(std::unique(ratios.begin(), ratios.end()), ratios.end());
  return ratios;
}

Sweep footprint_sweep(double width, double height, const Lens& lens, LensOptions options,
                      const std::vector<double>& ratios, int baseline_mesh) {
  validate_lens(lens, width, height);
  options.model = LensModel::kFocus;
  Sweep sweep;
  for (const double ratio : ratios) {
    require(std::isfinite(ratio) && ratio > lens.zoom && ratio <= 100, "footprint_sweep",
            "footprint ratio must be in (zoom, 100], got " + std::to_string(ratio));
    Lens swept = lens;
    swept.footprint = ratio;
    const LensResult solved = GeometricLens(width, height, options).solve({swept});
    sweep.ratios.push_back(ratio);
    sweep.points.push_back(measure("geometric", ratio, solved.warp, swept));
    const double zoom = std::max(1.0, sweep.points.back().zoom);
    sweep.bound.push_back(zoom > 1 ? radial_distortion_bound(zoom, ratio) : 0.0);
    sweep.rim_bound.push_back(zoom > 1 ? rim_distortion_bound(zoom, ratio) : 0.0);
    if (!lens.region.circle()) continue;  // the classic lenses are radial
    CircleLens target{lens.region.peak(), ratio * lens.region.reach(), zoom};
    target.focus_fraction = std::min(0.95, zoom / ratio);
    const double measure_radius = 0.05 * lens.region.reach();
    for (const ClassicLens kind : kClassicLenses) {
      const Magnification matched =
          match_classic_lens(kind, {target}, {measure_radius}, width, height, baseline_mesh);
      sweep.points.push_back(measure(to_string(kind), ratio, matched.warp, swept));
    }
  }
  return sweep;
}

Image plot_sweep(const Sweep& sweep, int width, int height) {
  require(width >= 320 && height >= 240, "plot_sweep",
          "the plot needs at least 320 x 240 pixels, got " + std::to_string(width) + " x " +
              std::to_string(height));
  require(!sweep.ratios.empty(), "plot_sweep", "the sweep is empty");
  Image image(width, height, 3, 255);
  const int left = 60, right = width - 170, top = 20, bottom = height - 50;
  const double x0 = *std::min_element(sweep.ratios.begin(), sweep.ratios.end());
  const double x1 = std::max(x0 + 1, *std::max_element(sweep.ratios.begin(), sweep.ratios.end()));
  // The y range: up to twice the largest bound or the geometric lens's maximum, whichever is more.
  double y1 = 0.5;
  for (size_t i = 0; i < sweep.bound.size(); ++i) y1 = std::max(y1, 2 * sweep.bound[i]);
  for (const SweepPoint& p : sweep.points)
    if (p.method == "geometric") y1 = std::max(y1, 1.1 * p.shape_max);
  auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * (right - left); };
  auto py = [&](double y) { return bottom - std::min(y, y1) / y1 * (bottom - top); };
  auto dot = [&](double x, double y, int r, std::array<uint8_t, 3> c, bool filled) {
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        const int X = int(std::lround(x)) + dx, Y = int(std::lround(y)) + dy;
        const bool edge = std::max(std::abs(dx), std::abs(dy)) == r;
        if (X < 0 || Y < 0 || X >= width || Y >= height || !(filled || edge)) continue;
        for (int k = 0; k < 3; ++k) image.at(X, Y)[k] = c[size_t(k)];
      }
  };
  auto line = [&](double xa, double ya, double xb, double yb, std::array<uint8_t, 3> c,
                  bool dashed) {
    const int steps = int(std::ceil(std::max(std::abs(xb - xa), std::abs(yb - ya)))) + 1;
    for (int s = 0; s <= steps; ++s)
      if (!dashed || (s / 4) % 2 == 0)
        dot(xa + (xb - xa) * s / steps, ya + (yb - ya) * s / steps, 0, c, true);
  };
  const std::array<uint8_t, 3> black{0, 0, 0}, grey{170, 170, 170};
  line(left, bottom, right, bottom, black, false);
  line(left, top, left, bottom, black, false);
  for (int k = 0; k <= 4; ++k) {
    const double y = y1 * k / 4;
    line(left, py(y), right, py(y), grey, true);
    draw_text(image, 4, int(py(y)) - 4, std::to_string(y).substr(0, 4), 1, black);
  }
  for (const double r : sweep.ratios)
    draw_text(image, int(px(r)) - 6, bottom + 6, std::to_string(r).substr(0, 4), 1, black);
  draw_text(image, left, bottom + 24, "footprint ratio F", 1, black);
  draw_text(image, left, 4, "largest shape distortion s1/s2 - 1", 1, black);
  // The bound, then one polyline per method in the order the sweep lists them.
  for (size_t i = 0; i + 1 < sweep.ratios.size(); ++i)
    line(px(sweep.ratios[i]), py(sweep.bound[i]), px(sweep.ratios[i + 1]), py(sweep.bound[i + 1]),
         black, true);
  const std::array<std::array<uint8_t, 3>, 8> colours = {{{200, 30, 30},
                                                          {120, 120, 120},
                                                          {30, 120, 200},
                                                          {30, 180, 200},
                                                          {150, 90, 30},
                                                          {60, 160, 60},
                                                          {150, 60, 170},
                                                          {230, 150, 20}}};
  std::vector<std::string> methods;
  for (const SweepPoint& p : sweep.points)
    if (std::find(methods.begin(), methods.end(), p.method) == methods.end())
      methods.push_back(p.method);
  for (size_t m = 0; m < methods.size(); ++m) {
    const std::array<uint8_t, 3> c = colours[m % colours.size()];
    const SweepPoint* last = nullptr;
    for (const SweepPoint& p : sweep.points) {
      if (p.method != methods[m]) continue;
      if (last) line(px(last->ratio), py(last->shape_max), px(p.ratio), py(p.shape_max), c, false);
      dot(px(p.ratio), py(p.shape_max), 3, c, p.uniformity <= 1.01);
      last = &p;
    }
    draw_text(image, right + 14, top + 14 * int(m), methods[m], 1, c);
  }
  draw_text(image, right + 14, top + 14 * int(methods.size()), "bound (dashed)", 1, black);
  draw_text(image, right + 14, top + 14 * int(methods.size() + 1), "hollow: focus not", 1, black);
  draw_text(image, right + 14, top + 14 * int(methods.size() + 2), "uniform", 1, black);
  return image;
}

}  // namespace geolens
