#include "geolens/lens/geometric_lens.h"

#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include "core/thread_pool.h"
#include "geolens/core/errors.h"
#include "lens/lens_pipeline.h"
#include "lens/solve_cache.h"

namespace geolens {

std::vector<std::string> zoom_warnings(const std::vector<Lens>& lenses, const LensResult& result) {
  // Six significant digits, as the CLI has always printed these zooms (3.20563).
  auto text = [](double value) { return (std::ostringstream() << value).str(); };
  std::vector<std::string> lines;
  for (size_t k = 0; k < lenses.size(); ++k) {
    const std::string lens = "lens " + std::to_string(k + 1);
    if (k < result.zoom_fit_reasons.size() && !result.zoom_fit_reasons[k].empty())
      lines.push_back(lens + " gets zoom " + text(result.zoom_fits[k]) + " of the " +
                      text(lenses[k].zoom) + " asked where it is, limited by " +
                      result.zoom_fit_reasons[k]);
    else if (k < result.zoom_measured.size() &&
             std::abs(result.zoom_measured[k] / lenses[k].zoom - 1) > 0.1)
      lines.push_back(lens + " reached zoom " + text(result.zoom_measured[k]) + " of the " +
                      text(lenses[k].zoom) + " requested");
  }
  return lines;
}

GeometricLens::GeometricLens(double width, double height, const LensOptions& options) {
  validate(options);
  LensContext context{width, height, options, make_grid(width, height, options.mesh),
                      std::make_shared<ThreadPool>(options.flatten.threads)};
  impl_ = std::make_shared<const Impl>(Impl{LensPipeline::make(std::move(context))});
}

const Grid& GeometricLens::grid() const { return impl_->pipeline->context().grid; }
double GeometricLens::width() const { return impl_->pipeline->context().width; }
double GeometricLens::height() const { return impl_->pipeline->context().height; }
const LensOptions& GeometricLens::options() const { return impl_->pipeline->context().options; }

LensResult GeometricLens::solve_with_heights(const std::vector<Lens>& lenses,
                                             const std::vector<double>& heights) const {
  require(heights.size() == lenses.size(), "GeometricLens::solve_with_heights",
          "one height per lens needed, got " + std::to_string(heights.size()) + " for " +
              std::to_string(lenses.size()) + " lenses");
  const LensPipeline& pipeline = *impl_->pipeline;
  const FittedLenses fit = pipeline.unfitted(lenses);
  SolveCache cache;
  return pipeline.solve_once(fit.box, fit.lenses, pipeline.solved_mesh(fit, heights), heights,
                             cache, {}, 1);
}

LensResult GeometricLens::solve(const std::vector<Lens>& asked, const SolveControl& control) const {
  const LensPipeline& pipeline = *impl_->pipeline;
  const FittedLenses fit = pipeline.fitted(asked, nullptr, false);
  const std::vector<double> h = pipeline.start_heights(fit);
  SolveCache cache;
  return pipeline.calibrated(fit, pipeline.solved_mesh(fit, h), h, cache, control);
}

}  // namespace geolens
