// Polygon and mask regions (roi.h): their depth and thickness fields sampled from a DepthRaster.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/geometry/roi.h"
#include "geolens/io/image.h"
#include "geometry/distance_field.h"
#include "geometry/mask_contour.h"
#include "geometry/polygon.h"
#include "geometry/roi_impl.h"

namespace geolens {
namespace {

// A polygon's raster has 1-pixel cells, but at least kMinCells and at most kMaxCells nodes
// along the long side of its bounding box padded by kPadding outside nodes on every side.
constexpr int kMaxCells = 1024;
constexpr int kMinCells = 64;
constexpr int kPadding = 2;
// Within kExactCells cells of a polygon's boundary, b is measured on its edges; over the next
// kExactCells it blends linearly into the raster's b.
constexpr double kExactCells = 2;

/// The fields of a polygon: a from the raster; b exact near the boundary (so that it is 0 on the
/// polygon itself, not on the raster's approximation of it) and from the raster deeper inside.
struct PolygonField {
  DepthRaster raster;
  PolygonIndex index;
  double exact;  // pixels: kExactCells cells

  double boundary_distance(const Eigen::Vector2d& p) const {
    if (!index.contains(p)) return 0;
    const double near = index.boundary_distance(p, 2 * exact);
    if (near <= exact) return near;
    const double w = (near - exact) / exact;
    return (1 - w) * near + w * raster.boundary_distance(p);
  }
};

/// The shape of a polygon already validated.
std::shared_ptr<FieldShape> polygon_shape(const std::vector<Eigen::Vector2d>& vertices) {
  Eigen::AlignedBox2d box;
  for (const Eigen::Vector2d& v : vertices) box.extend(v);
  const Eigen::Vector2d extent = box.sizes();
  const double long_side = extent.maxCoeff();
  const double cell = std::clamp(1.0, long_side / (kMaxCells - 2 * kPadding),
                                 long_side / (kMinCells - 2 * kPadding));
  // Nodes at the centres of cells, the box padded by kPadding - 1/2 cells on every side.
  const int width = int(std::ceil(extent.x() / cell)) + 2 * kPadding;
  const int height = int(std::ceil(extent.y() / cell)) + 2 * kPadding;
  const Eigen::Vector2d origin = box.min().array() - (kPadding - 0.5) * cell;
  const std::vector<uint8_t> inside = rasterize_polygon(vertices, width, height, origin, cell);
  require(std::find(inside.begin(), inside.end(), 1) != inside.end(), "Region::polygon",
          "the polygon is too thin: no node of its raster (cell " + number_text(cell) +
              " px) lies inside it");
  const double exact = kExactCells * cell;
  auto field = std::make_shared<const PolygonField>(PolygonField{
      depth_raster(inside, width, height, origin, cell), PolygonIndex(vertices, 2 * exact), exact});

  auto shape = std::make_shared<FieldShape>();
  shape->name = "polygon";
  shape->box = box;
  shape->anchor_points = vertices;
  shape->as_polygon = vertices;
  shape->depth_at = [field](const Eigen::Vector2d& p) {
    return depth_from_distances(field->raster.axis_distance(p), field->boundary_distance(p));
  };
  shape->thickness_at = [field](const Eigen::Vector2d& p) {
    return field->raster.axis_distance(p) + field->boundary_distance(p);
  };
  shape->peak_point = field->raster.peak;
  shape->largest_thickness = shape->thickness_at(shape->peak_point);
  shape->distance_at = [field, vertices](const Eigen::Vector2d& p) {
    if (field->index.contains(p)) return 0.0;
    // Every edge (the index's bands serve short reaches; this one is unbounded).
    double d2 = std::numeric_limits<double>::infinity();
    for (size_t i = 0, j = vertices.size() - 1; i < vertices.size(); j = i++)
      d2 = std::min(d2, segment_squared_distance(p, vertices[j], vertices[i]));
    return std::sqrt(d2);
  };
  for (const Eigen::Vector2d& v : vertices)
    shape->largest_reach = std::max(shape->largest_reach, (v - shape->peak_point).norm());
  return shape;
}

/// The polygon of a mask blob's smoothed outline (mask_contours, geometry/mask_contour.h), if
/// the blob has one simple outline (no hole, no part too thin for the smoothing) that encloses
/// its area within kMaskAreaTolerance. Nodes as from_mask's: (i, j) at origin + (i, j).
constexpr double kMaskAreaTolerance = 0.05;
std::optional<std::vector<Eigen::Vector2d>> mask_outline(const std::vector<uint8_t>& inside,
                                                         int width, int height,
                                                         const Eigen::Vector2d& origin) {
  const std::vector<std::vector<Eigen::Vector2d>> loops =
      mask_contours(inside, width, height, origin);
  if (loops.size() != 1) return std::nullopt;
  try {
    validate_polygon(loops[0]);
  } catch (const InvalidInput&) {
    return std::nullopt;
  }
  const std::vector<Eigen::Vector2d>& loop = loops[0];
  double twice_area = 0;  // the shoelace formula
  for (size_t k = 0; k < loop.size(); ++k) {
    const Eigen::Vector2d &p = loop[k], &q = loop[(k + 1) % loop.size()];
    twice_area += p.x() * q.y() - p.y() * q.x();
  }
  const double pixels = double(std::count(inside.begin(), inside.end(), 1));
  if (std::abs(std::abs(twice_area) / 2 - pixels) > kMaskAreaTolerance * pixels)
    return std::nullopt;
  return loops[0];
}

/// Whether every vertex of the polygon `loop` is seen from `p`: no edge crosses the segment
/// from p to it by more than kGraze pixels on either side. The focus lens finds a polygon's
/// footprint along rays from its peak and magnifies what lies behind a notch that faces away from
/// the peak too little (a disk with a slot from its centre to its rim fits zoom 1.74 of 2 and 1 of
/// 3 at mesh 250); such a blob stays a raster mask.
constexpr double kGraze = 1.5;  // pixels
bool seen_whole_from(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& loop) {
  const size_t n = loop.size();
  auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return u.x() * v.y() - u.y() * v.x();
  };
  for (size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d& v = loop[k];
    for (size_t e = 0; e < n; ++e) {
      if (e == k || (e + 1) % n == k) continue;  // the edges at v
      const Eigen::Vector2d &a = loop[e], &b = loop[(e + 1) % n];
      // A crossing: a and b on either side of the line p-v and farther from it than kGraze, p
      // and v on either side of a-b. An edge that grazes the line hides no more than a sliver.
      const double length = (v - p).norm();
      const double da = cross(v - p, a - p) / length, db = cross(v - p, b - p) / length;
      const double dp = cross(b - a, p - a), dv = cross(b - a, v - a);
      if (da * db < 0 && std::min(std::abs(da), std::abs(db)) > kGraze && dp * dv < 0) return false;
    }
  }
  return true;
}

/// An 8-connected blob of a mask's pixels.
struct Blob {
  int x0, y0, x1, y1;  // pixel bounding box, inclusive
  int pixels = 0;
};

/// A mask's blobs and the blob of each pixel (its index, -1 for none), row-major.
struct Blobs {
  std::vector<Blob> blobs;
  std::vector<int> label;
};

/// Labels `id` the blob of pixel (x, y) of `mask` (not yet labelled) by a flood fill over the
/// 8-neighbours; returns the blob. `stack`: scratch.
Blob flood_blob(const Image& mask, int x, int y, int id, std::vector<int>& label,
                std::vector<int>& stack) {
  const int w = mask.width, h = mask.height;
  Blob blob{x, y, x, y, 0};
  label[size_t(y) * w + x] = id;
  stack.assign(1, y * w + x);
  while (!stack.empty()) {
    const int px = stack.back() % w, py = stack.back() / w;
    stack.pop_back();
    ++blob.pixels;
    blob.x0 = std::min(blob.x0, px);
    blob.x1 = std::max(blob.x1, px);
    blob.y0 = std::min(blob.y0, py);
    blob.y1 = std::max(blob.y1, py);
    for (int qy = std::max(py - 1, 0); qy <= std::min(py + 1, h - 1); ++qy) {
      for (int qx = std::max(px - 1, 0); qx <= std::min(px + 1, w - 1); ++qx) {
        if (!mask.at(qx, qy)[0] || label[size_t(qy) * w + qx] >= 0) continue;
        label[size_t(qy) * w + qx] = id;
        stack.push_back(qy * w + qx);
      }
    }
  }
  return blob;
}

/// The 8-connected blobs of the mask's non-zero first-channel pixels, labelled in raster order.
Blobs label_blobs(const Image& mask) {
  const int w = mask.width, h = mask.height;
  Blobs found;
  found.label.assign(size_t(w) * h, -1);
  std::vector<int> stack;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!mask.at(x, y)[0] || found.label[size_t(y) * w + x] >= 0) continue;
      found.blobs.push_back(flood_blob(mask, x, y, int(found.blobs.size()), found.label, stack));
    }
  }
  return found;
}

/// Blob `id`'s nodes, 1 inside: one per pixel centre, the blob's box padded by one outside pixel
/// on every side (width x height nodes, row-major); `w`: the mask's width.
std::vector<uint8_t> blob_nodes(const Blob& b, int id, const std::vector<int>& label, int w,
                                int width, int height) {
  std::vector<uint8_t> inside(size_t(width) * height, 0);
  for (int y = b.y0; y <= b.y1; ++y) {
    for (int x = b.x0; x <= b.x1; ++x) {
      inside[size_t(y - b.y0 + 1) * width + (x - b.x0 + 1)] =
          uint8_t(label[size_t(y) * w + x] == id);
    }
  }
  return inside;
}

/// The blob's pixel box as a region's bounds: from its first pixel's corner to past its last.
Eigen::AlignedBox2d pixel_box(const Blob& b) {
  return Eigen::AlignedBox2d(Eigen::Vector2d(b.x0, b.y0), Eigen::Vector2d(b.x1 + 1, b.y1 + 1));
}

/// The shape of blob `b` as the polygon of its smooth outline (so a lens's mesh follows its
/// boundary, as a polygon's), named a mask and with no anchors; null if the blob has no such
/// outline or its peak does not see it whole. `inside`: its nodes, (i, j) at origin + (i, j).
std::shared_ptr<FieldShape> outline_shape(const Blob& b, const std::vector<uint8_t>& inside,
                                          int width, int height, const Eigen::Vector2d& origin) {
  const std::optional<std::vector<Eigen::Vector2d>> outline =
      mask_outline(inside, width, height, origin);
  if (!outline) return nullptr;
  const std::shared_ptr<FieldShape> shape = polygon_shape(*outline);
  if (!seen_whole_from(shape->peak_point, *outline)) return nullptr;
  shape->name = "mask";
  shape->anchor_points.clear();
  shape->box.extend(pixel_box(b));
  return shape;
}

/// The pixels of blob `id` with a 4-neighbour outside it, as their corners (x, y); `w` x `h`: the
/// mask's size.
std::shared_ptr<std::vector<Eigen::Vector2d>> boundary_pixels(const Blob& b, int id,
                                                              const std::vector<int>& label, int w,
                                                              int h) {
  auto in_blob = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < w && y < h && label[size_t(y) * w + x] == id;
  };
  auto edge = std::make_shared<std::vector<Eigen::Vector2d>>();  // pixel corners (x, y)
  for (int y = b.y0; y <= b.y1; ++y) {
    for (int x = b.x0; x <= b.x1; ++x) {
      if (in_blob(x, y) &&
          !(in_blob(x - 1, y) && in_blob(x + 1, y) && in_blob(x, y - 1) && in_blob(x, y + 1)))
        edge->emplace_back(x, y);
    }
  }
  return edge;
}

/// The shape of blob `id` as its raster: depth and thickness from the nodes' distance fields
/// (`inside`, width x height nodes at origin + (i, j)), the distance outside to its boundary
/// pixels; `w` x `h`: the mask's size.
std::shared_ptr<FieldShape> raster_shape(const Blob& b, int id, const std::vector<int>& label,
                                         int w, int h, const std::vector<uint8_t>& inside,
                                         int width, int height, const Eigen::Vector2d& origin) {
  auto raster =
      std::make_shared<const DepthRaster>(depth_raster(inside, width, height, origin, 1.0));

  auto shape = std::make_shared<FieldShape>();
  shape->name = "mask";
  shape->box = pixel_box(b);
  shape->depth_at = [raster](const Eigen::Vector2d& p) {
    return depth_from_distances(raster->axis_distance(p), raster->boundary_distance(p));
  };
  shape->thickness_at = [raster](const Eigen::Vector2d& p) {
    return raster->axis_distance(p) + raster->boundary_distance(p);
  };
  shape->peak_point = raster->peak;
  shape->largest_thickness = shape->thickness_at(shape->peak_point);
  // Outside, the distance to the nearest pixel square on the blob's boundary (one with a
  // 4-neighbour outside the blob), found by a scan over them.
  const std::shared_ptr<std::vector<Eigen::Vector2d>> edge = boundary_pixels(b, id, label, w, h);
  for (const Eigen::Vector2d& e : *edge) {
    const Eigen::Vector2d far =
        (shape->peak_point - e)
            .cwiseAbs()
            .cwiseMax((shape->peak_point - e - Eigen::Vector2d::Ones()).cwiseAbs());
    shape->largest_reach = std::max(shape->largest_reach, far.norm());
  }
  auto pixels = std::make_shared<const std::vector<uint8_t>>(inside);
  shape->distance_at = [edge, pixels, width, height, x0 = b.x0 - 1,
                        y0 = b.y0 - 1](const Eigen::Vector2d& p) {
    const double px = std::floor(p.x()) - x0, py = std::floor(p.y()) - y0;
    if (px >= 0 && py >= 0 && px < width && py < height &&
        (*pixels)[size_t(py) * size_t(width) + size_t(px)])
      return 0.0;
    double best = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector2d& e : *edge) {
      const Eigen::Vector2d d = (e - p).cwiseMax(p - e - Eigen::Vector2d::Ones()).cwiseMax(0.0);
      best = std::min(best, d.squaredNorm());
    }
    return std::sqrt(best);
  };
  return shape;
}

}  // namespace

Region Region::polygon(const std::vector<Eigen::Vector2d>& vertices) {
  validate_polygon(vertices, "Region::polygon");
  return Region(polygon_shape(vertices));
}

std::vector<Region> Region::from_mask(const Image& mask, size_t* dropped) {
  require(mask.width > 0 && mask.height > 0 && mask.channels >= 1 &&
              mask.pixels.size() == size_t(mask.width) * mask.height * mask.channels,
          "Region::from_mask",
          "malformed image: " + std::to_string(mask.width) + " x " + std::to_string(mask.height) +
              " x " + std::to_string(mask.channels) + " with " +
              std::to_string(mask.pixels.size()) + " bytes");
  const int w = mask.width, h = mask.height;
  const Blobs found = label_blobs(mask);
  const std::vector<Blob>& blobs = found.blobs;
  require(!blobs.empty(), "Region::from_mask", "the mask has no non-zero pixel");
  const size_t specks = size_t(std::count_if(
      blobs.begin(), blobs.end(), [](const Blob& b) { return b.pixels < kMinMaskBlobPixels; }));
  require(specks < blobs.size(), "Region::from_mask",
          "every blob of the mask (" + std::to_string(blobs.size()) + ") has fewer than " +
              std::to_string(kMinMaskBlobPixels) + " pixels");
  if (dropped) *dropped = specks;

  std::vector<Region> regions;
  for (size_t id = 0; id < blobs.size(); ++id) {
    const Blob& b = blobs[id];
    if (b.pixels < kMinMaskBlobPixels) continue;
    const int width = b.x1 - b.x0 + 3, height = b.y1 - b.y0 + 3;
    const std::vector<uint8_t> inside = blob_nodes(b, int(id), found.label, w, width, height);
    const Eigen::Vector2d origin(b.x0 - 0.5, b.y0 - 0.5);
    // A blob with one smooth outline is that polygon; any other its raster.
    std::shared_ptr<FieldShape> shape = outline_shape(b, inside, width, height, origin);
    if (!shape) shape = raster_shape(b, int(id), found.label, w, h, inside, width, height, origin);
    regions.push_back(Region(std::move(shape)));
  }
  return regions;
}

}  // namespace geolens
