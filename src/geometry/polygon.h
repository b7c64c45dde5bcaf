#pragma once
// Simple polygons: validation, reading from a text file, point location and rasterization.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace geolens {

/// Throws InvalidInput("<function>: ...") unless `vertices` (pixels, either orientation, not
/// closed explicitly) form a simple polygon: at least 3 vertices, all finite, non-zero area, no
/// two edges meeting except consecutive ones at their shared vertex (so no repeated vertex, no
/// vertex touching another edge, no edge folding back on the previous one). The message names
/// the offending vertices. O(n^2) in the number of vertices.
void validate_polygon(const std::vector<Eigen::Vector2d>& vertices,
                      const char* function = "validate_polygon");

/// Reads polygon vertices from a text file: one "x y" pair (pixels) per line, separated by
/// blanks, a comma or a semicolon ("x y", "x,y", "x, y", "x;y"); blank lines and everything from
/// a '#' to the end of its line are skipped; a last vertex equal to the first (a closed ring, as
/// GeoJSON and many tools write it) is dropped. Throws
/// InvalidInput naming the file for an unreadable file, and the file and line number for a line
/// that is not two finite numbers. The shape is not checked: see validate_polygon.
std::vector<Eigen::Vector2d> read_polygon_file(const std::string& path);

/// The distance from p to the segment a-b (to a where a == b), pixels.
double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b);

/// The closed loop `loop` simplified by Douglas and Peucker's algorithm: its first point and the
/// point farthest from it kept, and between two kept points the farthest point of the loop from
/// their segment kept while it is more than `tolerance` (pixels) from it, recursively (done with
/// a stack of its own, so a loop of millions of points does not exhaust the call stack). Every
/// dropped point is within `tolerance` of the simplified loop. O(n log n) typically, O(n^2) at
/// worst.
std::vector<Eigen::Vector2d> simplify_loop(const std::vector<Eigen::Vector2d>& loop,
                                           double tolerance);
/// Its square (no square root: for the nearest of many segments).
double segment_squared_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                const Eigen::Vector2d& b);

/// Which nodes of the raster origin + cell * (i, j), i in [0, width), j in [0, height) (pixels),
/// lie inside the polygon (a valid one, see validate_polygon). Returns width * height flags,
/// row-major. The inside test is the crossing rule of PolygonIndex::contains, so a node on the
/// boundary may go either way.
std::vector<uint8_t> rasterize_polygon(const std::vector<Eigen::Vector2d>& vertices, int width,
                                       int height, const Eigen::Vector2d& origin, double cell);

/// Point location against a simple polygon: its edges bucketed in horizontal bands, so that a
/// query looks only at the edges crossing the bands within its reach.
class PolygonIndex {
 public:
  /// @param vertices a valid polygon (see validate_polygon), pixels
  /// @param band height of the bands, pixels (> 0); about the reach of boundary_distance queries
  PolygonIndex(std::vector<Eigen::Vector2d> vertices, double band);

  /// Whether p is inside: an odd number of edges cross the horizontal ray from p towards +x
  /// (an edge counts when one end is above p and the other on or below it). A point exactly on
  /// the boundary may go either way; its boundary_distance is 0.
  bool contains(const Eigen::Vector2d& p) const;

  /// The Euclidean distance from p to the polygon boundary (pixels) if it is less than `reach`,
  /// else `reach`. Exact up to rounding.
  double boundary_distance(const Eigen::Vector2d& p, double reach) const;

 private:
  std::vector<Eigen::Vector2d> vertices_;  // edge e joins vertex e and vertex (e + 1) mod n
  double bottom_ = 0;                      // smallest vertex y: band k is [bottom_ + k band_, ...)
  double band_ = 1;
  std::vector<int> first_;  // #bands + 1: edges_[first_[k] .. first_[k + 1]) meet band k
  std::vector<int> edges_;
};

}  // namespace geolens
