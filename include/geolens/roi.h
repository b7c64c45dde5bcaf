#pragma once
// Regions of interest: where a lens magnifies.

#include <Eigen/Core>

namespace geolens {

/// A circular region of interest in source pixels.
struct CircleRoi {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< pixels
  double radius = 0;                                 ///< pixels, > 0

  /// Normalized depth of point p (pixels): 1 at the centre, 0 on and outside the circle,
  /// 1 - distance / radius in between.
  double depth(const Eigen::Vector2d& p) const;
};

}  // namespace geolens
