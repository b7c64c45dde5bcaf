#pragma once
// Private: the paper's pipeline (LensModel::kLift, kField, and kAuto choosing between them per
// solve; docs/design.md "Zoom, not height"): the image's grid or a local patch, subdivided where
// the bump bends, lifted, the texture re-mapped harmonically (kLift), flattened, and the bump
// heights calibrated by repeated solves until each lens's measured zoom meets its request.

#include <vector>

#include "lens/lens_pipeline.h"

namespace geolens {

class LiftPipeline final : public LensPipeline {
 public:
  using LensPipeline::LensPipeline;

  LensModel model_for(const std::vector<Lens>& lenses) const override;
  FittedLenses fitted(const std::vector<Lens>& lenses, SolveCache* cache,
                      bool draft) const override;
  FittedLenses unfitted(const std::vector<Lens>& lenses) const override;
  PlanarMesh solved_mesh(const FittedLenses& fit, const std::vector<double>& h) const override;
  LensResult solve_once(const Eigen::AlignedBox2d& box, const std::vector<Lens>& lenses,
                        const PlanarMesh& mesh, const std::vector<double>& h, SolveCache& cache,
                        const SolveControl& control, int solve) const override;

 private:
  // The image, or a local patch around the lenses.
  Eigen::AlignedBox2d solved_box(const std::vector<Lens>& lenses) const;
  FlattenOptions flatten_options(LensModel model) const;
  // Texture coordinates of the lifted mesh (kLift), with the fold fallback; kField keeps them.
  void texture(const Lifted& lifted, LensResult& r) const;
};

}  // namespace geolens
