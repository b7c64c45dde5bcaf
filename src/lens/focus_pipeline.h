#pragma once
// Private: the focus model's pipeline (LensModel::kFocus, docs/design.md "Focus lenses"): the
// lenses fitted where they are (shared room, the largest zoom that fits, what the mesh holds),
// the mesh over their footprints made to follow the regions (or the last frame's, moved), the
// focus field and its start, one solve.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lens/lens_pipeline.h"

namespace geolens {

struct MeshMemo;

class FocusPipeline final : public LensPipeline {
 public:
  using LensPipeline::LensPipeline;
  /// The pipeline of a frame stretched by `stretch` (context: the frame's size), used through
  /// FittedLenses::frame (fitted makes it; it fits with fitted_here, never stretching again);
  /// its reasons name distances in the image's pixels.
  FocusPipeline(LensContext context, const Eigen::Vector2d& stretch)
      : LensPipeline(std::move(context)), stretch_(stretch) {}

  LensModel model_for(const std::vector<Lens>&) const override { return LensModel::kFocus; }
  FittedLenses fitted(const std::vector<Lens>& lenses, SolveCache* cache,
                      bool draft) const override;
  FittedLenses unfitted(const std::vector<Lens>& lenses) const override;
  PlanarMesh solved_mesh(const FittedLenses& fit, const std::vector<double>&) const override {
    return fit.mesh;
  }
  LensResult solve_once(const Eigen::AlignedBox2d& box, const std::vector<Lens>& lenses,
                        const PlanarMesh& mesh, const std::vector<double>& h, SolveCache& cache,
                        const SolveControl& control, int solve) const override;

 private:
  // The footprints' box, within the image.
  Eigen::AlignedBox2d solved_box(const std::vector<Lens>& lenses) const;
  // The vertices along the long side of the grid over `box` for `lenses`: the mesh option's, more
  // where a circle is smaller than 2 cells of it (up to kFinestGrid times as fine), so that the
  // mesh follows it (meshed_along_regions).
  int grid_vertices(const Eigen::AlignedBox2d& box, const std::vector<Lens>& lenses) const;
  // The side of a cell of that grid, pixels.
  double cell_size(const Eigen::AlignedBox2d& box, const std::vector<Lens>& lenses) const;
  // The grid over the footprints' box (`box`), made to follow every region's boundary and
  // footprint's edge and, unless a draft, refined where the start bends; `on_curve` as
  // conform_mesh gives it.
  BaseMesh base_mesh(const std::vector<Lens>& lenses, Eigen::AlignedBox2d& box, bool draft,
                     std::vector<int>* on_curve) const;
  // Whether every focus group's footprint, on the mesh of `box`, is clear of the image border.
  bool clear_of_border(const std::vector<Lens>& lenses, const Eigen::AlignedBox2d& box) const;
  std::optional<BaseMesh> moved_mesh(const MeshMemo& memo, const std::vector<Lens>& lenses,
                                     Eigen::AlignedBox2d& box) const;
  // The lenses at the largest zooms up to theirs that fit where they are, their footprints at
  // those zooms (fitting_zooms), with what limits each in `reasons`; lenses near each other
  // magnified as one where that gives them more, unless not `merge`.
  std::vector<Lens> fitting(const std::vector<Lens>& lenses, std::vector<std::string>& reasons,
                            bool merge) const;
  // fitted with or without merging lenses near each other (fitting); `merged` tells whether some
  // lenses were magnified as one.
  FittedLenses fitted_once(const std::vector<Lens>& lenses, bool merge, MeshMemo* memo, bool draft,
                           bool* merged = nullptr) const;
  // fitted in this pipeline's own frame.
  FittedLenses fitted_here(const std::vector<Lens>& lenses, SolveCache* cache, bool draft) const;

  // A stretched frame's pixels per image pixel along x and y (stretched_frame.h); (1, 1) for the
  // image's own pipeline.
  Eigen::Vector2d stretch_ = Eigen::Vector2d::Ones();
};

}  // namespace geolens
