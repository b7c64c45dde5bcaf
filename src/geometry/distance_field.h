#pragma once
// Euclidean distance transforms on a raster, the medial axis read off the feature transform, and
// the depth field of a region built on them (the two fields of roi.h).

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace geolens {

/// The exact Euclidean distance transform of a raster together with its feature (nearest-site)
/// transform.
struct DistanceTransform {
  std::vector<double> squared;  ///< width * height, row-major: squared distance to the nearest
                                ///< site, cells^2 (an integer), +infinity when there is no site
  std::vector<int> nearest;     ///< width * height: row-major index of that site, -1 if none
};

/// The distance transform of the non-zero nodes of `sites` (width * height, row-major, unit
/// spacing), separable as in Felzenszwalb & Huttenlocher, "Distance Transforms of Sampled
/// Functions", Theory of Computing 8 (2012): the nearest site in each column (two sweeps), then
/// along each row the lower envelope of the parabolas (x - q)^2 + column distance^2; linear time.
/// Ties between equally near sites go either way.
/// Throws InvalidInput unless width, height > 0 and sites.size() == width * height.
DistanceTransform distance_transform(const std::vector<uint8_t>& sites, int width, int height);

/// The medial axis (skeleton) of the non-zero nodes of `inside` (width * height, row-major),
/// from `outside`, the distance transform of its complement: the nodes where the nearest
/// boundary point jumps from one side of the shape to another. Returns width * height flags, 1 on
/// the axis. Throws InvalidInput when the sizes do not match.
///
/// Criterion. An inside node p and its inside right or lower neighbour q, with nearest outside
/// nodes f(p) != f(q), straddle the axis when the chord from f(p) to f(q) passes deep inside:
///
///     b(c) - 1.5 >= sin^2(theta / 2) r,    theta = 50 degrees,
///
/// with c the chord's midpoint, b(c) its distance to the nearest outside node, r the mean
/// distance from the midpoint of p and q to f(p) and f(q) (all in cells). Then the one of p and
/// q nearer the bisector of f(p) and f(q) is on the axis (both on a tie).
/// - When f(p) and f(q) lie on two straight sides meeting at a corner, b(c) = r sin^2(alpha / 2)
///   with alpha the angle they subtend, so this is the angle criterion alpha >= theta, which is
///   scale-free: a convex corner of interior angle phi grows a branch when 180 - phi >= theta
///   (right angles and star tips do; the shallow corners of a polygon approximating a curve,
///   which would each grow a ridge, do not).
/// - When they lie on one side, the chord runs along the boundary and b(c) stays within the
///   slack, whatever the angle. This is what rejects the jagged boundary of a raster: the
///   nearest outside node of a point deep inside a digitised straight side jumps between the
///   nodes nearest the true line, by up to about the distance itself, so the angle the two
///   feature points subtend is no guide there.
/// - The 1.5-cell slack absorbs the digitisation of b(c). It ends a branch where its corner is
///   still a few cells wide: r >= 1.5 / (sin^2(alpha / 2) - sin^2(theta / 2)), 4.7 cells for a
///   right angle, 2.1 for a star's 36-degree tip.
/// The deepest inside node (the centre of the largest inscribed disc) is always on the axis, so
/// the axis is never empty when there are both inside and outside nodes.
std::vector<uint8_t> medial_axis(const std::vector<uint8_t>& inside, int width, int height,
                                 const DistanceTransform& outside);

/// The depth field of a region sampled on a raster of nodes at origin + cell * (i, j),
/// i in [0, width), j in [0, height) (roi.h): b, the distance to the region boundary, and a, the
/// distance to its medial axis.
struct DepthRaster {
  int width = 0;                                     ///< nodes along x
  int height = 0;                                    ///< nodes along y
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< position of node (0, 0), pixels
  double cell = 1;                                   ///< node spacing, pixels
  /// width * height, pixels: at an inside node, b = (distance to the nearest outside node) -
  /// cell / 2, the boundary being taken halfway between the last inside and first outside node;
  /// -cell / 2 at an outside node, so that the bilinear interpolation crosses 0 there.
  std::vector<float> boundary;
  std::vector<float> axis;  ///< width * height: a, distance to the nearest axis node, pixels
  Eigen::Vector2d peak = Eigen::Vector2d::Zero();  ///< the deepest axis node, pixels (below)

  /// b at p (pixels): bilinear in the nodes, clamped to >= 0; 0 outside the raster.
  double boundary_distance(const Eigen::Vector2d& p) const;
  /// a at p (pixels): bilinear in the nodes; 0 outside the raster.
  double axis_distance(const Eigen::Vector2d& p) const;
};

/// The depth raster of the non-zero nodes of `inside` (width * height, row-major) at
/// origin + cell * (i, j) (pixels; cell > 0): the exact distance transform of the outside
/// nodes, medial_axis, and a second distance transform to the axis. The peak is, among the axis
/// nodes within one cell of the largest b, the one nearest their centroid, so that a plateau of
/// equally deep nodes (the centre line of a rectangle) peaks in its middle. Throws InvalidInput
/// for mismatched sizes, cell <= 0, no inside node, or an inside node on the raster border (pad
/// the raster by at least one outside node).
DepthRaster depth_raster(const std::vector<uint8_t>& inside, int width, int height,
                         const Eigen::Vector2d& origin, double cell);

/// The normalized depth from the distance a to the medial axis and b to the boundary (pixels):
/// b / (a + b), 0 when b <= 0 (on and outside the boundary), 1 on the axis.
double depth_from_distances(double a, double b);

}  // namespace geolens
