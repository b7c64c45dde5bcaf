#include "lens/lift_pipeline.h"

#include "geolens/geometry/subdivide.h"
#include "lens/solve_cache.h"
#include "lens/texture_map.h"

namespace geolens {

LensModel LiftPipeline::model_for(const std::vector<Lens>& lenses) const {
  return resolved_model(c_.options.model, lenses);
}

Eigen::AlignedBox2d LiftPipeline::solved_box(const std::vector<Lens>& lenses) const {
  const Eigen::AlignedBox2d image(Eigen::Vector2d::Zero(), Eigen::Vector2d(c_.width, c_.height));
  if (c_.options.extent == Extent::kGlobal || lenses.empty()) return image;
  Eigen::AlignedBox2d box;
  for (const Lens& lens : lenses) {
    const Eigen::Vector2d centre = lens.region.bounds().center();
    const Eigen::Vector2d half = 0.5 * lens.region.bounds().sizes().array() +
                                 (c_.options.extent_factor - 1) * lens.region.size();
    box.extend(centre - half).extend(centre + half);
  }
  return box.intersection(image);
}

// The image's grid, or one over the local patch whose border carries the sides flags so the
// flattening pins it. Nothing is fitted: the calibration finds each lens's height.
FittedLenses LiftPipeline::fitted(const std::vector<Lens>& lenses, SolveCache*, bool) const {
  return unfitted(lenses);
}

FittedLenses LiftPipeline::unfitted(const std::vector<Lens>& lenses) const {
  for (const Lens& lens : lenses) validate_lens(lens, c_.width, c_.height);
  FittedLenses fit;
  fit.lenses = lenses;
  fit.box = solved_box(lenses);
  const Eigen::AlignedBox2d image(Eigen::Vector2d::Zero(), Eigen::Vector2d(c_.width, c_.height));
  if (fit.box.isApprox(image)) {
    fit.mesh = BaseMesh(c_.grid);
    return fit;
  }
  fit.mesh = BaseMesh(make_grid(fit.box.sizes().x(), fit.box.sizes().y(), c_.options.mesh));
  fit.mesh.V.rowwise() += fit.box.min().transpose();
  return fit;
}

// The grid subdivided where the bump of heights `h` bends.
PlanarMesh LiftPipeline::solved_mesh(const FittedLenses& fit, const std::vector<double>& h) const {
  return subdivide(
      fit.mesh, [&](const Eigen::Vector2d& p) { return lift_height(fit.lenses, h, p); },
      c_.options.subdivision);
}

FlattenOptions LiftPipeline::flatten_options(LensModel model) const {
  FlattenOptions o = c_.options.flatten;
  if (c_.options.extent == Extent::kLocal) o.boundary = Boundary::kFixed;
  if (model == LensModel::kField) {
    // The rest areas already weigh the magnified triangles; the paper's (1 + h) A weights on
    // top made the focus so stiff that the context folded into a band one triangle wide.
    o.standard = Standard::kScaled;
    o.weights = FlattenWeights::kCotan;
  }
  return o;
}

void LiftPipeline::texture(const Lifted& lifted, LensResult& r) const {
  if (r.model == LensModel::kField) {
    r.warp.source = r.mesh.V;
    return;
  }
  const TextureWeights weights = c_.options.texture;
  std::vector<char> fixed(lifted.inside.size());
  for (size_t i = 0; i < fixed.size(); ++i) fixed[i] = !lifted.inside[i] || r.mesh.sides[i] != 0;
  r.warp.source = harmonic_texture(lifted.V, r.mesh.F, fixed, r.mesh.V, weights);
  if (weights == TextureWeights::kCotan && count_folds(r.warp.source, r.mesh.F) > 0) {
    // Negative cotan weights folded the map (steep walls): redo it with non-negative weights.
    r.warp.source =
        harmonic_texture(lifted.V, r.mesh.F, fixed, r.mesh.V, TextureWeights::kPositiveCotan);
    r.texture_fallback = true;
  }
}

LensResult LiftPipeline::solve_once(const Eigen::AlignedBox2d& box, const std::vector<Lens>& lenses,
                                    const PlanarMesh& mesh, const std::vector<double>& h,
                                    SolveCache& cache, const SolveControl& control,
                                    int solve) const {
  const auto start = Clock::now();
  LensResult r;
  r.model = model_for(lenses);
  r.lift_heights_px = h;
  r.mesh = mesh;
  r.box = box;
  const Lifted lifted = lift(r.mesh.V, lenses, h);
  r.timings.lift = ms_since(start);
  const auto t = Clock::now();
  texture(lifted, r);
  r.timings.texture = ms_since(t);

  const FlattenOptions options = flatten_options(r.model);
  prepare_flattener(lifted, FocusConstraints{}, options, r, cache);

  // A lens dragged steadily moves its flattening steadily: a prediction is the better start
  // (unless it folds a triangle; after a stop or a jump it costs at most an iteration).
  const auto flatten = [&](const SolveControl& progress) {
    const bool predicted = cache.predicted.rows() == cache.flat.rows();
    return cache.flattener->solve(cache.flat, predicted ? &cache.predicted : nullptr, &progress);
  };
  flatten_and_finish(flatten, lenses, lifted, options.boundary, control, solve, start, cache, r);
  return r;
}

}  // namespace geolens
