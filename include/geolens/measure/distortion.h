#pragma once
// Measuring a WarpMesh: per-triangle magnification, shape distortion and flips.

#include <Eigen/Core>

#include "geolens/warp/warp_mesh.h"

namespace geolens {

/// Per-triangle measures of the affine map source -> screen (Jacobian J, singular values
/// s1 >= s2 >= 0).
struct TriangleDistortion {
  Eigen::VectorXd magnification;  ///< #F sqrt(s1 s2) = sqrt|det J|: linear magnification
  Eigen::VectorXd conformal;      ///< #F s1 / s2 - 1: 0 for a similarity (shape kept)
  Eigen::VectorXd source_area;    ///< #F triangle area in the source, pixels^2
  Eigen::Matrix<bool, Eigen::Dynamic, 1> flipped;  ///< #F det J <= 0
};

/// Measures every triangle of `mesh`. Triangles degenerate in the source get magnification 0,
/// conformal distortion +inf and count as flipped.
TriangleDistortion measure_triangles(const WarpMesh& mesh);

/// Area-weighted mean magnification of the triangles whose source centroid lies within
/// `radius` pixels of `point` (source pixels); the triangle containing the point if none does.
/// Throws InvalidInput if the point is in no triangle and no centroid is near.
double magnification_at(const WarpMesh& mesh, const TriangleDistortion& measures,
                        const Eigen::Vector2d& point, double radius);

/// The same, measuring only the triangles it needs (for interactive use).
double magnification_at(const WarpMesh& mesh, const Eigen::Vector2d& point, double radius);

/// The radius over which a lens's zoom is measured at its peak (GeometricLens's
/// LensResult::zoom_measured, and the classic lenses matched to it): a grid cell of the solved
/// area, and at least 0.05 of the region's size (docs/design.md, "Zoom, not height"). Pixels.
/// @param region_size  the region's size (Region::size), pixels
/// @param solved_side  the long side of the solved area (LensResult::box), pixels
/// @param mesh         grid vertices along that side (LensOptions::mesh), >= 2
double zoom_measure_radius(double region_size, double solved_side, int mesh);

struct DistortionSummary {
  double conformal_mean = 0;  ///< source-area-weighted mean of s1 / s2 - 1
  double conformal_max = 0;
  int flipped = 0;
  /// Some triangle collapsed (conformal_max above kDegenerateConformal): the figures then say
  /// how badly, not what a picture shows (the field model on a paragraph measured 8.3e14).
  bool degenerate() const { return !(conformal_max <= kDegenerateConformal); }
  static constexpr double kDegenerateConformal = 1e6;
};

DistortionSummary summarize(const TriangleDistortion& measures);

}  // namespace geolens
