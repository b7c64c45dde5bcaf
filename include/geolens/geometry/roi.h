#pragma once
// Regions of interest: where a lens magnifies, and the normalized depth field the lift shapes.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace geolens {

struct Image;

/// A circle, for what treats circles specially (a mesh that follows them, the radial lenses).
struct Circle {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< pixels
  double radius = 1;                                 ///< pixels, > 0
};

/// What a kind of region answers (the fields are those of Region, below). geolens's own are the
/// circle, the simple polygon and the mask blob; implement this to add another (a polygon with
/// holes, several polygons as one region, an analytic shape) and wrap it in a Region: nothing in
/// the lenses, measures or reports switches on the kind. Implementations are immutable and
/// their calls thread-safe.
class RegionShape {
 public:
  virtual ~RegionShape() = default;
  /// A short name: "circle", "polygon", "mask", ... (reports print it).
  virtual std::string kind() const = 0;
  virtual Eigen::AlignedBox2d bounds() const = 0;  ///< Region::bounds: bounding box, pixels
  virtual Eigen::Vector2d peak() const = 0;        ///< Region::peak: deepest and thickest point
  virtual double size() const = 0;                 ///< Region::size: the largest thickness, pixels
  virtual double reach() const = 0;  ///< Region::reach: farthest point from peak(), pixels
  /// Region::depth at `p` (pixels): in [0, 1], 0 on and outside the boundary, 1 on the medial axis.
  virtual double depth(const Eigen::Vector2d& p) const = 0;
  /// Region::thickness at `p`: the local half-width, pixels.
  virtual double thickness(const Eigen::Vector2d& p) const = 0;
  /// Region::distance from `p` to the region, pixels: 0 inside.
  virtual double distance(const Eigen::Vector2d& p) const = 0;
  /// The points that define the region and must lie in the image for a lens on it: a circle's
  /// centre, a polygon's vertices; none for a mask blob (it comes from an image of that size).
  virtual std::vector<Eigen::Vector2d> anchors() const = 0;
  /// The circle the region is, if it is one.
  virtual std::optional<Circle> circle() const { return std::nullopt; }
  /// The simple polygon the region is, if it is one (its vertices, pixels): a mesh can then
  /// follow its boundary exactly.
  virtual std::optional<std::vector<Eigen::Vector2d>> outline() const { return std::nullopt; }
};

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
  /// The fewest pixels a blob of a mask needs to be a region (from_mask); smaller ones are speckle.
  static constexpr int kMinMaskBlobPixels = 4;
  /// Every 8-connected blob of non-zero pixels of `mask` (first channel), one region each, in
  /// raster order of their first pixel. A blob whose smoothed outline (mask_contours,
  /// geometry/mask_contour.h: within about half a pixel of its pixel squares, corners rounded) is
  /// one simple polygon that encloses its area within 5 % and is seen whole from its peak (no
  /// notch facing away from it, which the focus lens cannot open) is that polygon, so a lens's mesh
  /// follows its boundary (outline() gives it); any other (with a hole, a thin part, a deep notch)
  /// is its pixel squares. Either is kind "mask" with no anchors. Blobs of fewer than
  /// kMinMaskBlobPixels pixels (speckle: a noisy mask of 961 one-pixel blobs made 961 lenses) are
  /// left out and counted in `*dropped` if given. Throws InvalidInput for an empty mask or one
  /// whose every blob is that small.
  static std::vector<Region> from_mask(const Image& mask, size_t* dropped = nullptr);
  /// Any other kind of region; throws InvalidInput for a null shape.
  explicit Region(std::shared_ptr<const RegionShape> shape);

  std::string kind() const;  ///< RegionShape::kind
  /// The circle the region is, if it is one.
  std::optional<Circle> circle() const;
  /// The simple polygon the region is, if it is one (RegionShape::outline).
  std::optional<std::vector<Eigen::Vector2d>> outline() const;
  /// Bounding box, pixels.
  Eigen::AlignedBox2d bounds() const;
  /// Where the depth is largest and the region thickest: the centre of a circle, the point of
  /// the medial axis with the largest thickness otherwise. Zoom is measured there.
  Eigen::Vector2d peak() const;
  /// The largest thickness, pixels: the radius of a circle.
  double size() const;
  /// The depth at `p` (pixels): in [0, 1], 0 on and outside the boundary, 1 on the medial axis.
  double depth(const Eigen::Vector2d& p) const;
  /// The thickness at `p`: the local half-width of the region, pixels (the circle's radius).
  double thickness(const Eigen::Vector2d& p) const;
  /// Distance from p to the region, pixels: 0 inside, the Euclidean distance to the nearest
  /// point of the region outside (exact for circles, polygons and a mask blob's outline; to the
  /// nearest pixel square of a mask blob without one, up to rounding).
  double distance(const Eigen::Vector2d& p) const;
  /// The largest distance from peak() to a point of the region, pixels: the radius of a
  /// circle, half the length of a thin strip measured from its middle.
  double reach() const;
  /// RegionShape::anchors: a circle's centre, a polygon's vertices, nothing for a mask blob.
  std::vector<Eigen::Vector2d> anchors() const;

  /// The region moved by `offset` (pixels), its fields shared with this one rather than made
  /// again (a polygon's rasters: a region dragged is moved, not rebuilt, every frame). Throws
  /// InvalidInput for a non-finite offset.
  Region translated(const Eigen::Vector2d& offset) const;

 private:
  std::shared_ptr<const RegionShape> shape_;  // immutable, so copies share it
};

}  // namespace geolens
