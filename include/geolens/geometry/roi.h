#pragma once
// Regions of interest: where a lens magnifies, and the normalized depth field the lift shapes.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

namespace geolens {

struct Image;

enum class RegionKind { kCircle, kPolygon, kMask };
std::string to_string(RegionKind kind);  ///< "circle" | "polygon" | "mask"

/// A region of interest in source pixels, with the two fields the lift needs at any point p:
///
/// - depth(p) in [0, 1]: 0 on and outside the boundary, 1 on the medial axis, continuous.
///   With b = distance to the boundary and a = distance to the medial axis, depth = b / (a + b).
///   For a circle the axis is the centre, so depth = 1 - |p - c| / r.
/// - thickness(p) = a + b in pixels: the local half-width of the region, continuous; the lift
///   scales a region's height by thickness / size() so a thin part gets a bump as steep as a
///   wide one, not the cliff the paper's single d_m normalisation leaves (design.md). For a
///   circle it is r everywhere.
///
/// Polygons and masks compute both fields on a raster (Euclidean distance transforms, medial
/// axis from the feature transform) and sample them bilinearly.
class Region {
 public:
  /// A circle; throws InvalidInput unless centre finite and radius finite and > 0.
  static Region circle(const Eigen::Vector2d& center, double radius);
  /// A simple polygon (vertices in pixels, either orientation, not closed explicitly). Throws
  /// InvalidInput for fewer than 3 vertices, zero area, self-intersections or non-finite values.
  static Region polygon(const std::vector<Eigen::Vector2d>& vertices);
  /// Every 8-connected blob of non-zero pixels of `mask` (first channel), one region each, in
  /// raster order of their first pixel. Throws InvalidInput for an empty mask.
  static std::vector<Region> from_mask(const Image& mask);

  RegionKind kind() const;
  /// Bounding box, pixels.
  Eigen::AlignedBox2d bounds() const;
  /// Where the depth is largest and the region thickest: the centre of a circle, the point of
  /// the medial axis with the largest thickness otherwise. Zoom is measured there.
  Eigen::Vector2d peak() const;
  /// The largest thickness, pixels: the radius of a circle.
  double size() const;
  double depth(const Eigen::Vector2d& p) const;
  double thickness(const Eigen::Vector2d& p) const;
  /// Distance from p to the region, pixels: 0 inside, the Euclidean distance to the nearest
  /// point of the region outside (exact for circles and polygons; to the nearest pixel square
  /// of a mask, up to rounding).
  double distance(const Eigen::Vector2d& p) const;
  /// The largest distance from peak() to a point of the region, pixels: the radius of a
  /// circle, half the length of a thin strip measured from its middle.
  double reach() const;
  /// For polygons: the vertices; empty otherwise.
  const std::vector<Eigen::Vector2d>& vertices() const;

  struct Impl;

 private:
  explicit Region(std::shared_ptr<const Impl> impl);
  std::shared_ptr<const Impl> impl_;  // immutable, so copies share it
};

}  // namespace geolens
