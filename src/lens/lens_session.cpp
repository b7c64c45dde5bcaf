#include "geolens/lens/lens_session.h"

#include <optional>
#include <utility>

#include "geolens/core/errors.h"
#include "lens/lens_pipeline.h"
#include "lens/solve_cache.h"

namespace geolens {

struct LensSession::State {
  SolveCache caches[2];         // full frames', drafts'
  Eigen::MatrixX2d change;      // what the last update changed in the flattening (#V x 2, or empty)
  std::vector<Lens> lenses;     // the last update's (fitted) lenses
  std::vector<double> heights;  // and their calibrated heights
  LensModel model = LensModel::kFocus;
};

namespace {

// The options of a session's drafts: its grid, if it has its own.
std::optional<LensOptions> draft_options(const LensOptions& options) {
  if (options.draft_mesh == 0 || options.draft_mesh == options.mesh) return std::nullopt;
  LensOptions o = options;
  o.mesh = options.draft_mesh;
  return o;
}

}  // namespace

LensSession::LensSession(double width, double height, const LensOptions& options)
    : lens_(width, height, options), state_(std::make_unique<State>()) {
  if (const std::optional<LensOptions> o = draft_options(options))
    draft_lens_.emplace(width, height, *o);
}
LensSession::~LensSession() = default;
LensSession::LensSession(LensSession&&) noexcept = default;
LensSession& LensSession::operator=(LensSession&&) noexcept = default;

void LensSession::reset() { state_ = std::make_unique<State>(); }

LensResult LensSession::update(const std::vector<Lens>& asked, const SolveControl& control,
                               bool draft) {
  State& s = *state_;
  SolveCache& cache = s.caches[draft ? 1 : 0];
  const LensPipeline& solver = *(draft && draft_lens_ ? *draft_lens_ : lens_).impl_->pipeline;
  const FittedLenses fit = solver.fitted(asked, &cache, draft);
  // A draft whose coarse mesh cannot hold a lens's zoom is solved in full: a drag shows the zoom
  // the lens gets at rest, not a frame at less (a circle sliding away from a side flickered to
  // 2.41 of 3 on the draft mesh at two places in 120).
  if (draft && fit.mesh_limited) return update(asked, control, false);
  // Start from the heights found last time for a lens of the same shape, size and zoom (and
  // model): after a move, one solve usually confirms them.
  const std::vector<Lens>& lenses = fit.lenses;
  const LensModel model = solver.model_for(lenses);
  const std::vector<double> h = solver.start_heights(fit, [&](size_t k) -> std::optional<double> {
    const Lens& lens = lenses[k];
    const bool known = k < s.lenses.size() && s.model == model && s.lenses[k].zoom == lens.zoom &&
                       s.lenses[k].profile == lens.profile &&
                       s.lenses[k].region.kind() == lens.region.kind() &&
                       s.lenses[k].region.size() == lens.region.size();
    return known ? std::optional<double>(s.heights[k]) : std::nullopt;
  });
  Eigen::MatrixX2d before = cache.flat;
  const Eigen::Vector2d box_before = cache.box.min();
  if (s.change.rows() == before.rows()) cache.predicted = before + s.change;
  LensResult r;
  try {
    r = solver.calibrated(fit, fit.mesh, h, cache, control);
  } catch (const Cancelled&) {
    // The cache holds a consistent flattener and the last finished flattening, but no steady
    // motion to predict from.
    s.change.resize(0, 2);
    cache.predicted.resize(0, 2);
    throw;
  }
  r.draft = draft && (draft_lens_ || (r.model == LensModel::kFocus &&
                                      solver.context().options.mesh_tolerance > 0));
  s.lenses = lenses;
  s.heights = r.model == LensModel::kFocus ? r.focus_log_zooms : r.lift_heights_px;
  s.model = r.model;
  s.change.resize(0, 2);
  if (before.rows() == cache.flat.rows()) {
    // In the current patch's coordinates (a local patch moves with its lens).
    before.rowwise() += (cache.box.min() - box_before).transpose();
    s.change = cache.flat - before;
  }
  return r;
}

}  // namespace geolens
