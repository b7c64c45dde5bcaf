#pragma once
// A planar mesh made to follow closed curves (circles, polygons, a lens's footprint edge), so that
// a map with a kink or a jump along a curve is represented exactly by a piecewise-linear one.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "geolens/geometry/grid.h"

namespace geolens {

/// A closed curve a mesh is made to follow, given by level(p) < 0 on one side, > 0 on the other,
/// 0 on the curve, continuous, and about the distance to the curve near it (pixels), which
/// decides the vertices moved onto it; a polygon is followed edge by edge instead.
struct MeshCurve {
  /// The polygon's vertices (pixels, either orientation), or empty for another curve.
  std::vector<Eigen::Vector2d> polygon;
  /// The level, pixels; positive outside `bounds`.
  std::function<double(const Eigen::Vector2d&)> level;
  /// A point of the curve near p (p within a few cells of it), pixels.
  std::function<Eigen::Vector2d(const Eigen::Vector2d&)> project;
  Eigen::AlignedBox2d bounds;  ///< holds the curve and its negative side, pixels
  /// Whether triangles with a corner on it are refined by their slope too
  /// (MeshRefinement::slope_tolerance): where the map bends most next to it.
  bool slope = false;
};

/// The circle of `center` and `radius` (pixels, > 0): level = distance to the centre - radius.
MeshCurve circle_curve(const Eigen::Vector2d& center, double radius);

/// The boundary of a simple polygon (vertices in pixels, either orientation), followed edge by
/// edge; its level is the signed distance to the boundary (negative inside). Throws
/// InvalidInput for an invalid polygon (validate_polygon).
MeshCurve polygon_curve(const std::vector<Eigen::Vector2d>& vertices);

/// Refinement of a conforming mesh where a map's linear interpolation misses it (conform_mesh).
struct MeshRefinement {
  /// The map (#P x 2 points in, #P x 2 out, pixels); none: no refinement.
  std::function<Eigen::MatrixX2d(const Eigen::MatrixX2d&)> map;
  double tolerance = 0.1;  ///< pixels of the map's output, > 0
  int max_passes = 8;      ///< >= 0
  /// Also split a triangle with a corner on a curve marked `slope` whose linear interpolant's
  /// slope is off by more than this fraction of its smaller singular value (the error of its
  /// shape), estimated from the map at its edges' midpoints; 0: only positions are looked at.
  double slope_tolerance = 0;
};

/// `mesh` made to follow every curve, in turn, so that afterwards no triangle has points on both
/// sides of any curve (a map with a kink or a jump along a curve is then represented exactly):
///
/// - a polygon: each of its vertices inside the mesh becomes a mesh vertex (the nearest free
///   vertex of the triangle holding it is moved there if its triangles keep a fifth of their
///   area, else that triangle is split there); then each edge in turn: free vertices closer than
///   `snap` (pixels, >= 0) to it are moved onto it (as above), and every triangle the edge still
///   crosses is split along it, at the exact crossings. Afterwards triangles at each polygon
///   vertex are split until each spans at most 30 degrees there (see fan_out in the source).
/// - another curve: free vertices closer than `snap` are moved onto it (project; as above), then
///   every triangle with vertices on both sides is split along it, at the points of its crossed
///   edges where the level is 0 (to 1e-12 of the edge). A curve that enters and leaves a
///   triangle through one edge is not followed there (a feature smaller than the mesh).
///
/// Then, with `refine.map`, up to max_passes times: every triangle with an edge whose midpoint
/// the map sends farther than `tolerance` from the mean of its ends' images, or whose centroid
/// it sends that far from the mean of its corners', or (with a corner on a `slope` curve) whose
/// slope is off by more than `slope_tolerance` of its smaller singular value, is split at the
/// midpoint of its longest edge (with the triangle across it, longest-edge propagation); a midpoint
/// of an edge along a curve is put on the curve (project). Last, slivers (an angle below 10
/// degrees) are made fatter by flipping edges (Delaunay's test, the smallest angle growing), except
/// edges along a curve or with a corner on a side, and flips that would leave more than 30 degrees
/// at a polygon vertex.
///
/// New vertices on an edge are shared by both its triangles. Vertices on a side of the mesh
/// (sides != 0) and vertices placed on an earlier curve do not move; a vertex added on an edge
/// keeps the side flags both its ends share. Curves closer than about a cell to each other or to
/// a side give thin triangles but no crossing. O(#F) per curve and per polygon edge. With
/// `on_curve`, it receives per vertex of the result the index of the curve the vertex was placed
/// on (the first, where several meet), or -1.
PlanarMesh conform_mesh(const PlanarMesh& mesh, const std::vector<MeshCurve>& curves, double snap,
                        const MeshRefinement& refine = {}, std::vector<int>* on_curve = nullptr);

}  // namespace geolens
