#pragma once
// Lifting the flat grid into a 3D bump over each region of interest (paper section 4).

#include <Eigen/Core>
#include <vector>

#include "geolens/profile.h"
#include "geolens/roi.h"

namespace geolens {

/// One lens: where, how much, and with which bump shape.
struct Lens {
  CircleRoi roi;
  double zoom = 2.0;  ///< requested magnification at the centre, in [1, 8]
  Profile profile = Profile::kGaussian;
};

/// Throws InvalidInput unless the lens is usable on a width x height image: finite values,
/// radius > 0, centre inside the image, zoom in [1, 8].
void validate_lens(const Lens& lens, double width, double height);

/// The lifted mesh: the grid's vertices with heights.
struct Lifted {
  Eigen::MatrixX3d V;     ///< #V x 3: x, y as the grid, z = max over lenses of h0 * profile, pixels
  Eigen::VectorXd level;  ///< #V: max over lenses of profile(depth) in [0, 1] (height / h0)
  std::vector<char> inside;  ///< #V: 1 where the vertex lies strictly inside some ROI
};

/// Lifts the 2D vertices `V` (#V x 2, pixels) over `lenses`, lens i with centre height
/// `heights[i]` (pixels, >= 0). Overlapping lenses combine by max.
Lifted lift(const Eigen::MatrixX2d& V, const std::vector<Lens>& lenses,
            const std::vector<double>& heights);

}  // namespace geolens
