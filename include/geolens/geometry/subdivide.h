#pragma once
// Adaptive, conforming refinement of the triangles the lift stretches or shears (paper 4).

#include <Eigen/Core>
#include <functional>

#include "geolens/geometry/grid.h"

namespace geolens {

/// Where subdivide refines a mesh (the triangles the lift stretches or shears) and in how many
/// rounds (LensOptions::subdivision).
struct SubdivisionOptions {
  /// An edge is split when its lifted 3D length exceeds this multiple of its planar length.
  double max_stretch = 1.6;
  /// A triangle whose smallest lifted angle is below this (degrees) has its longest lifted edge
  /// split (shear).
  double min_angle = 12.0;
  int max_levels = 0;  ///< bisection rounds, >= 0 (0 = no subdivision); two halve an edge
};

/// Throws InvalidInput unless max_stretch > 1, min_angle in [0, 60) and max_levels in [0, 8].
void validate(const SubdivisionOptions& options);

/// Refines `mesh` where the lift z = height(x, y) (pixels) stretches or shears it. Each round
/// marks the triangles with a lifted edge longer than max_stretch times its planar length or a
/// lifted angle below min_angle, and bisects each once at its longest edge with Rivara's
/// longest-edge propagation (M.-C. Rivara, "New longest-edge algorithms for the refinement
/// and/or improvement of unstructured triangulations", IJNME 1997): the result has no
/// T-junctions, stays a manifold disk, keeps every triangle's orientation, and on the grid's
/// right isosceles triangles produces right isosceles triangles only. New vertices lie at edge
/// midpoints (appended after the input's, which keep their indices); their heights are
/// evaluated from `height`, not interpolated, and a midpoint of a border edge gets the sides its
/// two ends share.
PlanarMesh subdivide(const PlanarMesh& mesh,
                     const std::function<double(const Eigen::Vector2d&)>& height,
                     const SubdivisionOptions& options);

}  // namespace geolens
