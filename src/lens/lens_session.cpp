#include "geolens/lens/lens_session.h"

#include <algorithm>
#include <optional>
#include <utility>

#include "geolens/core/errors.h"
#include "lens/lens_pipeline.h"
#include "lens/solve_cache.h"

namespace geolens {

struct LensSession::State {
  explicit State(size_t levels) : caches(levels) {}
  std::vector<SolveCache> caches;  // per level: full frames', then drafts' (LensSession::solve)
  Eigen::MatrixX2d change;      // what the last update changed in the flattening (#V x 2, or empty)
  std::vector<Lens> lenses;     // the last update's (fitted) lenses
  std::vector<double> heights;  // and their calibrated heights
  LensModel model = LensModel::kFocus;
};

namespace {

// The options of a session's draft grids, coarsest first: draft_mesh, then twice that, and so on
// while finer grids are still coarser than `mesh` (none where draft_mesh is 0 or `mesh`).
std::vector<LensOptions> draft_options(const LensOptions& options) {
  std::vector<LensOptions> grids;
  if (options.draft_mesh == 0 || options.draft_mesh == options.mesh) return grids;
  for (int mesh = options.draft_mesh; grids.empty() || mesh < options.mesh; mesh *= 2) {
    LensOptions o = options;
    o.mesh = mesh;
    grids.push_back(o);
  }
  return grids;
}

}  // namespace

LensSession::LensSession(double width, double height, const LensOptions& options)
    : lens_(width, height, options) {
  for (const LensOptions& o : draft_options(options)) drafts_.emplace_back(width, height, o);
  reset();
}
LensSession::~LensSession() = default;
LensSession::LensSession(LensSession&&) noexcept = default;
LensSession& LensSession::operator=(LensSession&&) noexcept = default;

void LensSession::reset() {
  state_ = std::make_unique<State>(1 + std::max<size_t>(drafts_.size(), 1));
}

LensResult LensSession::update(const std::vector<Lens>& asked, const SolveControl& control,
                               bool draft) {
  return solve(asked, control, draft ? 1 : 0);
}

LensResult LensSession::solve(const std::vector<Lens>& asked, const SolveControl& control,
                              size_t level) {
  State& s = *state_;
  SolveCache& cache = s.caches[level];
  const bool draft = level > 0;
  const LensPipeline& solver =
      *(draft && !drafts_.empty() ? drafts_[level - 1] : lens_).impl_->pipeline;
  const FittedLenses fit = solver.fitted(asked, &cache, draft);
  // A draft whose coarse mesh cannot hold a lens's zoom is solved on the next finer draft grid,
  // and in full after the finest: a drag shows the zoom the lens gets at rest, not a frame at
  // less (a circle sliding away from a side flickered to 2.41 of 3 on the draft mesh at two
  // places in 120).
  if (draft && fit.mesh_limited)
    return solve(asked, control, level < drafts_.size() ? level + 1 : 0);
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
  r.draft = draft && (!drafts_.empty() || (r.model == LensModel::kFocus &&
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
