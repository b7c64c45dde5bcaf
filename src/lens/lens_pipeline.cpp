#include "lens/lens_pipeline.h"

#include <cmath>
#include <utility>

#include "geolens/measure/distortion.h"
#include "lens/calibration.h"
#include "lens/focus_pipeline.h"
#include "lens/framing.h"
#include "lens/lift_pipeline.h"
#include "lens/solve_cache.h"
#include "lens/stretched_frame.h"

namespace geolens {

namespace {

// `control` with its progress numbered by the calibration's `solve`.
SolveControl numbered(const SolveControl& control, int solve) {
  SolveControl out{control.cancel, nullptr};
  if (control.progress)
    out.progress = [progress = control.progress, solve](const SolveProgress& p) {
      progress({solve, p.iteration, p.energy});
    };
  return out;
}

}  // namespace

std::unique_ptr<LensPipeline> LensPipeline::make(LensContext context) {
  if (context.options.model == LensModel::kFocus)
    return std::make_unique<FocusPipeline>(std::move(context));
  return std::make_unique<LiftPipeline>(std::move(context));
}

double LensPipeline::ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

LensResult LensPipeline::calibrated(const FittedLenses& fit, const PlanarMesh& mesh,
                                    const std::vector<double>& h, SolveCache& cache,
                                    const SolveControl& control) const {
  const LensPipeline& solver = fit.frame ? *fit.frame : *this;
  LensResult r = calibrate(
      fit.lenses, model_for(fit.lenses), h, c_.options.zoom_tolerance,
      c_.options.max_calibration_solves, [&](const std::vector<double>& heights, int solve) {
        return solver.solve_once(fit.box, fit.lenses, mesh, heights, cache, control, solve);
      });
  if (fit.frame) unstretch(r, fit.stretch, int(std::lround(c_.width)), int(std::lround(c_.height)));
  r.zoom_fits = fit.zoom_fits;
  r.zoom_fit_reasons = fit.zoom_fit_reasons;
  r.mesh_limited = fit.mesh_limited;
  return r;
}

void LensPipeline::prepare_flattener(const Lifted& lifted, const FocusConstraints& constraints,
                                     const FlattenOptions& options, LensResult& r,
                                     SolveCache& cache) const {
  const auto t = Clock::now();
  // A local patch has the same topology wherever it is, as long as its size is unchanged; a
  // focus lens's also needs the same pinned vertices.
  const bool same_topology =
      cache.flattener && cache.model == r.model && cache.flat.rows() == r.mesh.V.rows() &&
      (cache.box.sizes() - r.box.sizes()).norm() < 1e-9 && constraints.pinned == cache.pinned &&
      cache.faces.rows() == r.mesh.F.rows() && cache.faces == r.mesh.F;
  if (same_topology) {
    cache.flattener->reweight(lifted.V, lifted.level, lifted.log_zoom, constraints);
    const Eigen::RowVector2d shift = (r.box.min() - cache.box.min()).transpose();
    cache.flat.rowwise() += shift;
    if (cache.predicted.rows() == cache.flat.rows()) cache.predicted.rowwise() += shift;
  } else {
    cache.flattener = std::make_unique<Flattener>(lifted.V, r.mesh.F, lifted.level, r.mesh.sides,
                                                  options, lifted.log_zoom, constraints, c_.pool);
    cache.flat = r.mesh.V;
    cache.predicted.resize(0, 2);
  }
  cache.box = r.box;
  cache.pinned = constraints.pinned;
  cache.faces = r.mesh.F;
  cache.model = r.model;
  r.timings.factorize = ms_since(t);
}

std::vector<double> LensPipeline::start_heights(
    const FittedLenses& fit, const std::function<std::optional<double>(size_t)>& known) const {
  const LensModel model = model_for(fit.lenses);
  std::vector<double> h;
  for (size_t k = 0; k < fit.lenses.size(); ++k) {
    const Lens& lens = fit.lenses[k];
    const std::optional<double> last = lens.zoom == 1 || !known ? std::nullopt : known(k);
    h.push_back(lens.zoom == 1 ? 0.0 : last ? *last : initial_height(lens, model, fit.mesh.cell));
  }
  return h;
}

void LensPipeline::flatten_and_finish(
    const std::function<FlattenResult(const SolveControl&)>& flatten,
    const std::vector<Lens>& lenses, const Lifted& lifted, Boundary boundary,
    const SolveControl& control, int solve, Clock::time_point start, SolveCache& cache,
    LensResult& r) const {
  const auto t = Clock::now();
  r.flattening = flatten(numbered(control, solve));
  cache.predicted.resize(0, 2);
  cache.flat = r.flattening.X;
  r.timings.iterate = ms_since(t);

  const double width = c_.width, height = c_.height;
  r.lifted = lifted.V;
  r.flat = r.flattening.X;
  r.warp.F = r.mesh.F;
  r.warp.screen = frame(r.flat, boundary, width, height);
  r.warp.screen_width = int(std::lround(width));
  r.warp.screen_height = int(std::lround(height));
  const Eigen::AlignedBox2d image(Eigen::Vector2d::Zero(), Eigen::Vector2d(width, height));
  if (!r.box.isApprox(image)) add_identity_frame(r.warp, r.mesh, r.box, width, height);
  for (const Lens& lens : lenses) {
    const double radius =
        zoom_measure_radius(lens.region.size(), r.box.sizes().maxCoeff(), c_.options.mesh);
    r.zoom_measured.push_back(magnification_at(r.warp, lens.region.peak(), radius));
    r.zoom_parameter.push_back(lens.zoom);
  }
  r.solves = 1;
  r.timings.total = ms_since(start);
}

}  // namespace geolens
