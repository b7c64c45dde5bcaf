#pragma once
// Points mapped through a WarpMesh: forward (source -> screen) and inverse (screen -> source),
// each through a uniform-grid bucket index over the mesh's triangles.

#include <Eigen/Core>
#include <memory>
#include <optional>

#include "geolens/warp/warp_mesh.h"

namespace geolens {

/// The piecewise-linear map of a WarpMesh and its inverse, for single points and batches, from
/// any lens (the geometric lens and every classic lens alike: it reads only the WarpMesh).
///
/// A point is mapped by barycentric interpolation in the triangle that holds it. A point outside
/// a triangle by less than kEdgeTolerance times the triangle's altitude (all barycentric
/// coordinates >= -kEdgeTolerance) counts as inside it, so points on shared edges and on the
/// mesh's border find a triangle despite rounding. Of the triangles that hold a point (within
/// that tolerance) the first, the lowest row of F, is used: the one a linear scan over F would
/// find, also for a point on a shared edge or vertex. Triangles whose area is below 1e-12 of
/// their squared longest edge are never used (their neighbours cover their edges).
///
/// Outside the covered area (a point in no triangle) the single-point queries return an empty
/// std::optional and the batch queries a row of NaNs. Why not the identity: a WarpMesh says
/// nothing there, and a guess would be drawn in the wrong place. Source points outside the
/// image are not on the screen the warp frames; the ring a zoom-in lens hides under its inset
/// (classic_lens.h) is in no source triangle and is not shown anywhere, so a viewer or a
/// vector-data layer must skip it rather than draw it through the identity, on top of the
/// inset. A caller that wants the identity there writes `forward(p).value_or(p)`.
///
/// The inverse is well defined where screen triangles do not overlap, which holds for a warp
/// without flips (no measure_triangles(...).flipped, distortion.h). Where they do overlap (a folded
/// triangle, of negative screen area, lies over its neighbours) inverse(q) returns the preimage in
/// the first triangle that holds q, one of several; forward(inverse(q)) = q still holds.
///
/// The index: per side (source, screen), a uniform grid of square buckets over the bounding box
/// of the usable triangles, each bucket listing the triangles whose bounding box (widened by the
/// tolerance) meets it. The bucket side is kBucketScale times the square root of the side's
/// mean triangle area (about the side of a grid cell), widened where the triangles are few and
/// far apart so that there are O(#F) buckets. A bucket then lists about 6 triangles where the
/// triangles are near the mean size (measured 5.8 - 6.4 on the geometric lens at 100 and 200
/// vertices), fewer where they are larger and up to zoom^2 times more where a side's mesh is
/// that much finer than its mean (the source of a classic lens, regular on screen: at most 34
/// for zoom 3). Building costs O(#F) time and memory (1.0 ms at 100 x 100 vertices, 4.5 ms at
/// 200 x 200); a query O(triangles in its bucket): 50 - 60 / 80 - 90 ns (bench/README.md).
///
/// WarpMap keeps its own copy of the mesh, taken at construction, so it stays valid when the
/// WarpMesh it was built from changes or goes away (rebuild it for a new frame); copies of a
/// WarpMap share that copy and the indexes, which are immutable, so queries are const and may
/// run on several threads at once.
class WarpMap {
 public:
  static constexpr double kEdgeTolerance = 1e-9;  ///< barycentric, see the class comment
  static constexpr double kBucketScale = 1.0;     ///< bucket side over sqrt(mean triangle area)

  /// Validates and indexes `mesh`. Throws InvalidInput naming "WarpMap" if it has no
  /// triangles, source and screen differ in rows, an F index is outside [0, #V) or a vertex
  /// position is not finite.
  explicit WarpMap(WarpMesh mesh);

  /// Where the source point p (pixels) lands on the screen (pixels); empty if p is in no source
  /// triangle. Throws InvalidInput if p is not finite.
  std::optional<Eigen::Vector2d> forward(const Eigen::Vector2d& p) const;
  /// The source point (pixels) shown at the screen point q (pixels); empty if q is in no screen
  /// triangle. Throws InvalidInput if q is not finite.
  std::optional<Eigen::Vector2d> inverse(const Eigen::Vector2d& q) const;

  /// forward() of every row of `points` (#P x 2, source pixels): #P x 2 screen pixels, a row of
  /// NaNs where a point is in no triangle. Named apart from forward() so that forward({x, y})
  /// is not ambiguous with MatrixX2d's (rows, columns) constructor. Runs on the calling thread.
  /// A row of NaNs gives a row of NaNs (so inverse_batch(forward_batch(p)) chains); throws
  /// InvalidInput naming the first other row that is not finite.
  Eigen::MatrixX2d forward_batch(const Eigen::MatrixX2d& points) const;
  /// inverse() of every row of `points` (#P x 2, screen pixels): #P x 2 source pixels, NaN rows
  /// where a point is in no triangle. As forward_batch() otherwise.
  Eigen::MatrixX2d inverse_batch(const Eigen::MatrixX2d& points) const;

  /// The row of F whose source triangle holds p (the one forward(p) interpolates in), or -1.
  /// Throws InvalidInput if p is not finite.
  Eigen::Index source_triangle(const Eigen::Vector2d& p) const;
  /// The row of F whose screen triangle holds q (the one inverse(q) interpolates in), or -1.
  Eigen::Index screen_triangle(const Eigen::Vector2d& q) const;

  /// The mesh mapped through (the copy taken at construction).
  const WarpMesh& mesh() const;

  struct Impl;

 private:
  std::shared_ptr<const Impl> impl_;
};

/// The map of `warp` with its screen coordinates scaled from warp.screen_width x
/// warp.screen_height to width x height pixels, as render() scales them: so mapped features land
/// on the image rendered at that size. Throws InvalidInput naming "framed_warp_map" unless the
/// warp's frame and width, height are positive.
WarpMap framed_warp_map(const WarpMesh& warp, int width, int height);

}  // namespace geolens
