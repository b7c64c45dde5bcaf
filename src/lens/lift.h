#pragma once
// Private: lifting the flat grid into a 3D bump over each region of interest (paper section 4),
// the paper's pipeline's first step (lift_pipeline.h).

#include <Eigen/Core>
#include <vector>

#include "geolens/lens/lens.h"

namespace geolens {

/// The lifted mesh: the grid's vertices with heights.
struct Lifted {
  Eigen::MatrixX3d V;        ///< #V x 3: x, y as given, z = lift_height (pixels)
  Eigen::VectorXd level;     ///< #V: max over lenses of height / h0, in [0, 1] (for weights)
  std::vector<char> inside;  ///< #V: 1 where the vertex lies strictly inside some ROI
  /// #V: the lift read as a magnification field (LensModel::kField): the lenses' height / size
  /// combined like the heights, the natural log of the zoom the vertex asks for. Like the height,
  /// it rises from 0 on the boundary at the same rate in every part of a region, so a part of half
  /// the region's largest half-width asks for the square root of its peak zoom.
  Eigen::VectorXd log_zoom;
};

/// Height of one lens at p (pixels): h0 * thickness(p) / size() * profile(depth(p)), see roi.h.
double lens_height(const Lens& lens, double h0, const Eigen::Vector2d& p);

/// The height of the lift at p (pixels): the lenses' heights (lens i with peak height
/// `heights[i]`) combined by their 4-norm, (sum h_i^4)^(1/4): the one lens's height where the
/// others are 0, and no crease where two overlap (a max would leave one where they are equal).
double lift_height(const std::vector<Lens>& lenses, const std::vector<double>& heights,
                   const Eigen::Vector2d& p);

/// Lifts the 2D vertices `V` (#V x 2, pixels) over `lenses`, lens i with peak height
/// `heights[i]` (pixels, >= 0): z = lift_height.
Lifted lift(const Eigen::MatrixX2d& V, const std::vector<Lens>& lenses,
            const std::vector<double>& heights);

}  // namespace geolens
