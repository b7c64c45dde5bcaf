#pragma once
// Measuring a WarpMesh: per-triangle magnification, shape distortion and flips.

#include <Eigen/Core>
#include <string>
#include <vector>

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

/// A whole warp's shape distortion and flips, as run_stats_json reports them: summarize of
/// measure_triangles. Triangles degenerate in the source (s1 / s2 - 1 infinite) count as flipped
/// and are left out of the figures.
struct DistortionSummary {
  double conformal_mean = 0;  ///< source-area-weighted mean of s1 / s2 - 1
  double conformal_max = 0;   ///< the largest s1 / s2 - 1
  int flipped = 0;            ///< triangles with det J <= 0, degenerate ones included
  /// Some triangle collapsed (conformal_max above kDegenerateConformal): the figures then say
  /// how badly, not what a picture shows (the field model on a paragraph measured 8.3e14).
  bool degenerate() const { return !(conformal_max <= kDegenerateConformal); }
  static constexpr double kDegenerateConformal = 1e6;  ///< above it, degenerate()
};

/// The DistortionSummary of `measures` (measure_triangles of a warp).
DistortionSummary summarize(const TriangleDistortion& measures);

// Distortion per lens region (focus, transition, context) on any WarpMesh, the area the warp
// hides, and the paper's Eq. 7 shape energy of a flattening.

/// The default focus fraction, see CircleLens.
constexpr double kFocusFraction = 0.5;

/// A circular lens as the comparison sees it.
struct CircleLens {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< source pixels
  double radius = 1;                                 ///< source pixels, > 0
  double zoom = 1;                                   ///< magnification at the centre, >= 1
  /// The lenses with a flat top show it on this fraction of the radius on screen, in (0, 1).
  double focus_fraction = kFocusFraction;
};

/// Throws InvalidInput (naming `function`) unless the centre is finite, the radius finite and
/// > 0, the zoom finite and >= 1 and the focus fraction in (0, 1).
void validate(const CircleLens& lens, const char* function);

/// The focus is the inner part of the lens that a flat-top lens of the same radius and zoom
/// shows at its full zoom: the inner focus_fraction of the radius on screen, so the source disk
/// of radius focus_fraction * radius / zoom. It is a fixed fraction of what the user sees, and
/// it is where zoom_in, bifocal and the flat-top lenses are uniform by construction, so their
/// focus uniformity is exactly 1 and the question the focus answers is how far the other lenses
/// are from that. (A fixed source fraction such as 0.5 r would not do: at zoom 2 a lens of radius
/// r cannot show a source disk of r / 2 magnified 2x and still have a transition.)

/// Source radius of the focus: focus_fraction * radius / zoom, pixels.
double focus_radius(const CircleLens& lens);

/// Where a triangle lies for a lens (classify_triangles): its focus, the transition ring around
/// it, or the context beyond the lens.
enum class Zone { kFocus, kTransition, kContext };
std::string to_string(Zone zone);  ///< "focus" | "transition" | "context"

/// Where a triangle is: its zone and the lens that decides it.
struct TriangleZone {
  Zone zone = Zone::kContext;  ///< focus, transition or context of lens `lens`
  int lens = 0;                ///< index into the lenses
};

/// The zone of every triangle of `mesh`, the same rule for every lens method. A triangle's
/// distance from a lens is the mean of its three vertices' source distances from the centre
/// (on a mesh with vertices on the zone circles this is exact: a triangle on one side of a circle
/// has its mean on that side). The lens with the smallest distance / radius decides: the
/// triangle is in its focus when that distance is below focus_radius(lens), in its transition
/// when below the radius, in the context otherwise.
/// @return #F zones
std::vector<TriangleZone> classify_triangles(const WarpMesh& mesh,
                                             const std::vector<CircleLens>& lenses);

/// Statistics of the triangles of one zone (or of all: `overall`). Means are weighted by source
/// area. Flipped or degenerate triangles are counted in `flipped` and left out of every other
/// figure. A zone with no measured triangle has `triangles` 0 and every figure 0.
struct ZoneStatistics {
  int triangles = 0;                ///< measured (not flipped) triangles
  int flipped = 0;                  ///< triangles with det J <= 0 or degenerate
  double area = 0;                  ///< source area of the measured triangles, pixels^2
  double conformal_mean = 0;        ///< shape distortion s1 / s2 - 1
  double conformal_max = 0;         ///< the largest s1 / s2 - 1
  double magnification_min = 0;     ///< the smallest sqrt(s1 s2), the linear magnification
  double magnification_max = 0;     ///< the largest sqrt(s1 s2)
  double area_distortion_mean = 0;  ///< max(a, 1 / a) - 1 with a = s1 s2 the area scale: 0 when
                                    ///< the triangle keeps its area
};

/// What measure_regions returns: ZoneStatistics per zone and over the whole warp, how uniform
/// the foci are, and the source area the warp hides.
struct RegionStatistics {
  ///@{
  ZoneStatistics focus, transition, context, overall;  ///< per zone (classify_triangles); all
  ///@}
  /// Max / min magnification over the measured focus triangles of one lens, the largest over the
  /// lenses (1 = a uniform focus); 0 when no lens has a measured focus triangle.
  double focus_uniformity = 0;
  /// Source area not shown on screen, pixels^2: the source image area minus the source area of
  /// the triangles whose screen centroid lies inside the screen frame (screen_width x
  /// screen_height), at least 0. It counts content left out of the mesh (an inset covering what
  /// is under it) and content pushed off the frame; content hidden under a fold is not counted
  /// (flips are reported instead).
  double occluded_area = 0;
  double occluded_percent = 0;  ///< occluded_area over the source image area, in percent
};

/// Measures `mesh` per zone of `lenses` (at least one).
/// @param measures  measure_triangles(mesh)
/// @param source_width, source_height  size of the source image, pixels (> 0)
RegionStatistics measure_regions(const WarpMesh& mesh, const TriangleDistortion& measures,
                                 const std::vector<CircleLens>& lenses, double source_width,
                                 double source_height);

/// The paper's Eq. 7 shape distortion of a flattening, per triangle:
/// E_i = sum_{edges j} w_ij ||e_j - M_i e_j^std||^2, with e^std the edges of the triangle laid
/// isometrically in the plane from the lifted mesh (the paper's standard triangle, Fig. 4), e the
/// edges of the flattened triangle, M_i the rotation closest to the triangle's Jacobian
/// standard -> flat (the rigid metric, alpha = 0: distortion is measured from rigid, whatever
/// metric the solve used) and w_ij = cot of the angle opposite edge j in the standard triangle.
/// The paper's importance factor (1 + h) A of Eq. 2 is left out so the energy measures shape
/// only. Equal to 2 A_i ||J_i - M_i||_F^2 = 2 A_i ((s1 - 1)^2 + (s2 - 1)^2), A_i the standard
/// triangle's area.
/// @param V3  #V x 3 lifted vertices, pixels
/// @param F   #F x 3 triangles
/// @param X   #V x 2 flattened vertices, pixels
/// @return    #F energies, pixels^2
Eigen::VectorXd eq7_energy(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                           const Eigen::MatrixX2d& X);

}  // namespace geolens
