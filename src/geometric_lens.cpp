#include "geolens/geometric_lens.h"

#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "geolens/distortion.h"
#include "geolens/errors.h"

namespace geolens {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// First guess of the centre height for a zoom: h0 / r per unit of log(zoom), measured with the
// default options (cotan texture, paper weights) on a 100x100 grid at zoom 1.5 to 3.
double initial_height(const Lens& lens) {
  const double per_log_zoom[] = {1.08, 2.3, 1.95};  // gaussian, sphere, mesa
  return lens.region.size() * per_log_zoom[int(lens.profile)] * std::log(lens.zoom);
}

// Scales the flattening to the frame: sliding and fixed borders already fill the image; a free
// flattening is scaled uniformly to fit and centred.
Eigen::MatrixX2d frame(const Eigen::MatrixX2d& X, Boundary boundary, double width, double height) {
  if (boundary != Boundary::kFree) return X;
  const Eigen::Vector2d lo = X.colwise().minCoeff(), hi = X.colwise().maxCoeff();
  const Eigen::Vector2d extent = hi - lo;
  const double scale = std::min(width / extent.x(), height / extent.y());
  const Eigen::RowVector2d offset(0.5 * (width - scale * extent.x()),
                                  0.5 * (height - scale * extent.y()));
  return ((X.rowwise() - lo.transpose()) * scale).rowwise() + offset;
}

}  // namespace

void validate(const LensOptions& o) {
  require(o.mesh >= 4 && o.mesh <= 1000, "validate",
          "mesh must be in [4, 1000] vertices per side, got " + std::to_string(o.mesh));
  require(std::isfinite(o.zoom_tolerance) && o.zoom_tolerance > 0, "validate",
          "zoom tolerance must be positive");
  require(o.max_calibration_solves >= 1, "validate", "at least one calibration solve needed");
  validate(o.subdivision);
  validate(o.flatten);
}

GeometricLens::GeometricLens(double width, double height, const LensOptions& options)
    : width_(width), height_(height), options_(options) {
  validate(options);
  grid_ = make_grid(width, height, options.mesh);
}

// The stages after the lift: texture coordinates (with the fold fallback), then the framing and
// the zoom measured at each lens's peak once `r.flattening` is known.
void GeometricLens::texture(const Lifted& lifted, LensResult& r) const {
  std::vector<char> fixed(lifted.inside.size());
  for (size_t i = 0; i < fixed.size(); ++i) fixed[i] = !lifted.inside[i] || r.mesh.sides[i] != 0;
  r.warp.source = harmonic_texture(lifted.V, r.mesh.F, fixed, r.mesh.V, options_.texture);
  if (options_.texture == TextureWeights::kCotan && count_folds(r.warp.source, r.mesh.F) > 0) {
    // Negative cotan weights folded the map (steep walls): redo it with non-negative weights.
    r.warp.source =
        harmonic_texture(lifted.V, r.mesh.F, fixed, r.mesh.V, TextureWeights::kPositiveCotan);
    r.texture_fallback = true;
  }
}

void GeometricLens::finish(const std::vector<Lens>& lenses, const Lifted& lifted,
                           LensResult& r) const {
  r.lifted = lifted.V;
  r.flat = r.flattening.X;
  r.warp.F = r.mesh.F;
  r.warp.screen = frame(r.flat, options_.flatten.boundary, width_, height_);
  r.warp.screen_width = int(std::lround(width_));
  r.warp.screen_height = int(std::lround(height_));
  for (const Lens& lens : lenses) {
    const double radius = std::max(grid_.cell, 0.05 * lens.region.size());
    r.zoom_measured.push_back(magnification_at(r.warp, lens.region.peak(), radius));
  }
  r.solves = 1;
}

LensResult GeometricLens::solve_with_heights(const std::vector<Lens>& lenses,
                                             const std::vector<double>& heights) const {
  const auto start = Clock::now();
  LensResult r;
  r.heights = heights;
  r.mesh = subdivide(
      grid_,
      [&](const Eigen::Vector2d& p) {
        double z = 0;
        for (size_t k = 0; k < lenses.size(); ++k)
          z = std::max(z, lens_height(lenses[k], heights[k], p));
        return z;
      },
      options_.subdivision);
  const Lifted lifted = lift(r.mesh.V, lenses, heights);
  r.timings.lift = ms_since(start);

  auto t = Clock::now();
  texture(lifted, r);
  r.timings.texture = ms_since(t);

  t = Clock::now();
  const Flattener flattener(lifted.V, r.mesh.F, lifted.level, r.mesh.sides, options_.flatten);
  r.timings.factorize = ms_since(t);

  t = Clock::now();
  r.flattening = flattener.solve(r.mesh.V);
  r.timings.iterate = ms_since(t);

  finish(lenses, lifted, r);
  r.timings.total = ms_since(start);
  return r;
}

// The interactive path: the base grid (no subdivision, so the topology and the symbolic
// factorization stay), the flattener refitted numerically, and the previous flattening as the
// starting point.
LensResult GeometricLens::solve_cached(const std::vector<Lens>& lenses,
                                       const std::vector<double>& heights) {
  const auto start = Clock::now();
  LensResult r;
  r.heights = heights;
  r.mesh = grid_;
  const Lifted lifted = lift(r.mesh.V, lenses, heights);
  r.timings.lift = ms_since(start);

  auto t = Clock::now();
  texture(lifted, r);
  r.timings.texture = ms_since(t);

  t = Clock::now();
  if (cache_.flattener) {
    cache_.flattener->reweight(lifted.V, lifted.level);
  } else {
    cache_.flattener = std::make_unique<Flattener>(lifted.V, r.mesh.F, lifted.level, r.mesh.sides,
                                                   options_.flatten);
    cache_.flat = grid_.V;
  }
  r.timings.factorize = ms_since(t);

  t = Clock::now();
  r.flattening = cache_.flattener->solve(cache_.flat);
  cache_.flat = r.flattening.X;
  r.timings.iterate = ms_since(t);

  finish(lenses, lifted, r);
  r.timings.total = ms_since(start);
  return r;
}

LensResult GeometricLens::solve(const std::vector<Lens>& lenses) const {
  std::vector<double> h;
  for (const Lens& lens : lenses) h.push_back(lens.zoom == 1 ? 0.0 : initial_height(lens));
  return calibrate(lenses, h, [&](const std::vector<double>& heights) {
    return solve_with_heights(lenses, heights);
  });
}

const LensResult& GeometricLens::update(const std::vector<Lens>& lenses) {
  // Start from the heights found last time for a lens of the same shape, size and zoom: after a
  // move, one solve usually confirms them.
  std::vector<double> h;
  for (size_t k = 0; k < lenses.size(); ++k) {
    const Lens& lens = lenses[k];
    const bool known = k < cache_.lenses.size() && cache_.lenses[k].zoom == lens.zoom &&
                       cache_.lenses[k].profile == lens.profile &&
                       cache_.lenses[k].region.kind() == lens.region.kind() &&
                       cache_.lenses[k].region.size() == lens.region.size();
    h.push_back(lens.zoom == 1 ? 0.0 : known ? cache_.result.heights[k] : initial_height(lens));
  }
  cache_.result = calibrate(
      lenses, h, [&](const std::vector<double>& heights) { return solve_cached(lenses, heights); });
  cache_.lenses = lenses;
  return cache_.result;
}

LensResult GeometricLens::calibrate(
    const std::vector<Lens>& lenses, std::vector<double> h,
    const std::function<LensResult(const std::vector<double>&)>& run) const {
  for (const Lens& lens : lenses) validate_lens(lens, width_, height_);
  const size_t n = lenses.size();
  // Per lens, a bracket [lo, hi] of heights on f(h) = log(zoom(h)) - log(target), f(0) < 0,
  // refined by false position (Illinois variant: an end kept twice has its f halved).
  std::vector<double> lo(n, 0), hi(n, -1), f_lo(n), f_hi(n, 0);
  std::vector<int> last_side(n, 0);
  for (size_t k = 0; k < n; ++k) f_lo[k] = -std::log(lenses[k].zoom);
  StageTimings sum;
  LensResult best;
  double best_miss = std::numeric_limits<double>::infinity();
  for (int solve = 1;; ++solve) {
    LensResult r = run(h);
    sum.lift += r.timings.lift;
    sum.texture += r.timings.texture;
    sum.factorize += r.timings.factorize;
    sum.iterate += r.timings.iterate;
    sum.total += r.timings.total;
    // Keep the solve whose worst lens is closest to its zoom, should calibration not converge.
    double miss = 0;
    for (size_t k = 0; k < n; ++k)
      miss = std::max(miss, std::abs(std::log(r.zoom_measured[k] / lenses[k].zoom)));
    bool done = true;
    for (size_t k = 0; k < n; ++k) {
      if (h[k] == 0) continue;
      const double gain = std::log(r.zoom_measured[k]);
      const double f = gain - std::log(lenses[k].zoom);
      if (std::abs(f) <= std::log1p(options_.zoom_tolerance)) continue;
      done = false;
      const int side = f < 0 ? -1 : 1;
      if (side < 0) {
        lo[k] = h[k];
        f_lo[k] = f;
        if (last_side[k] < 0) f_hi[k] *= 0.5;
      } else {
        hi[k] = h[k];
        f_hi[k] = f;
        if (last_side[k] > 0) f_lo[k] *= 0.5;
      }
      last_side[k] = side;
      if (hi[k] < 0) {
        // No upper end yet: extrapolate log(zoom) linearly through h = 0, at most doubling.
        h[k] = gain > 0 ? std::min(2.0 * h[k], h[k] * std::log(lenses[k].zoom) / gain) : 2.0 * h[k];
      } else {
        h[k] = lo[k] + (hi[k] - lo[k]) * f_lo[k] / (f_lo[k] - f_hi[k]);
      }
    }
    if (miss < best_miss) {
      best_miss = miss;
      best = std::move(r);
    }
    if (done || solve >= options_.max_calibration_solves) {
      best.solves = solve;
      break;
    }
  }
  best.timings = sum;
  return best;
}

}  // namespace geolens
