#pragma once
// Brute-force polygon queries, references for the tests of polygon.h and roi.h.

#include <Eigen/Core>
#include <vector>

namespace geolens::testing {

/// Even-odd point in polygon over every edge (vertices in pixels, closed implicitly).
bool brute_inside(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p);

/// Distance from p to the nearest edge, over every edge, pixels.
double brute_boundary_distance(const std::vector<Eigen::Vector2d>& polygon,
                               const Eigen::Vector2d& p);

}  // namespace geolens::testing
