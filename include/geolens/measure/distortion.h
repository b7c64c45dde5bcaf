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

struct DistortionSummary {
  double conformal_mean = 0;  ///< source-area-weighted mean of s1 / s2 - 1
  double conformal_max = 0;
  int flipped = 0;
};

DistortionSummary summarize(const TriangleDistortion& measures);

}  // namespace geolens
