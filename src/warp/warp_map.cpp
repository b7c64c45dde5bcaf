#include "geolens/warp/warp_map.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geolens/core/errors.h"

namespace geolens {

namespace {

// A triangle of one side, ready for the barycentric test: its first vertex and the inverse of
// [b - a, c - a], so that (l1, l2) = inverse * (p - a) and p = a + l1 (b - a) + l2 (c - a).
struct Locator {
  Eigen::Vector2d a;
  Eigen::Matrix2d inverse;
};

// The triangle a point is in, and its barycentric coordinates there (weights 1 - l1 - l2, l1,
// l2 of its vertices 0, 1, 2); f = -1 for none.
struct Hit {
  Eigen::Index f = -1;
  double l1 = 0, l2 = 0;
};

// One side's triangles (source or screen positions) bucketed on a uniform grid (warp_map.h).
struct SideIndex {
  SideIndex(const Eigen::MatrixX3i& F, const Eigen::MatrixX2d& V);
  Hit locate(const Eigen::Vector2d& p) const;

  std::vector<Locator> locators;  // #F; only the usable ones are in buckets
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double inverse_side = 0;  // 1 / bucket side, 1 / pixels
  int columns = 0, rows = 0;
  std::vector<int> start;      // columns * rows + 1: bucket k lists triangles[start[k], start[k+1])
  std::vector<int> triangles;  // rows of F, ascending within each bucket
};

SideIndex::SideIndex(const Eigen::MatrixX3i& F, const Eigen::MatrixX2d& V) {
  const Eigen::Index m = F.rows();
  locators.resize(size_t(m));
  std::vector<Eigen::AlignedBox2d> boxes(static_cast<size_t>(m));  // empty for an unusable triangle
  Eigen::AlignedBox2d all;
  double area = 0;
  int usable = 0;
  for (Eigen::Index f = 0; f < m; ++f) {
    const Eigen::Vector2d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::Vector2d e1 = b - a, e2 = c - a;
    const double det = e1.x() * e2.y() - e1.y() * e2.x();  // twice the signed area
    const double longest2 = std::max({e1.squaredNorm(), e2.squaredNorm(), (c - b).squaredNorm()});
    if (!(std::abs(det) > 2e-12 * longest2)) continue;
    Locator& t = locators[size_t(f)];
    t.a = a;
    t.inverse << e2.y(), -e2.x(), -e1.y(), e1.x();
    t.inverse /= det;
    // A point the tolerance admits is at most kEdgeTolerance altitudes, so at most that many
    // longest edges, outside the triangle.
    const double pad = 2 * WarpMap::kEdgeTolerance * std::sqrt(longest2);
    Eigen::AlignedBox2d& box = boxes[size_t(f)];
    box.extend(a).extend(b).extend(c);
    box.min().array() -= pad;
    box.max().array() += pad;
    all.extend(box);
    area += std::abs(det) / 2;
    ++usable;
  }
  if (usable == 0) return;
  const Eigen::Vector2d extent = all.sizes();
  const double n = usable;
  const double side =
      std::max({WarpMap::kBucketScale * std::sqrt(area / n),
                std::sqrt(extent.x() * extent.y() / (4 * n)), extent.maxCoeff() / (4 * n)});
  origin = all.min();
  inverse_side = 1 / side;
  columns = int(extent.x() * inverse_side) + 1;
  rows = int(extent.y() * inverse_side) + 1;
  auto range = [&](const Eigen::AlignedBox2d& box) {
    const Eigen::Vector2d lo = (box.min() - origin) * inverse_side,
                          hi = (box.max() - origin) * inverse_side;
    return Eigen::Array4i(
        std::clamp(int(lo.x()), 0, columns - 1), std::clamp(int(hi.x()), 0, columns - 1),
        std::clamp(int(lo.y()), 0, rows - 1), std::clamp(int(hi.y()), 0, rows - 1));
  };
  // Two passes: count per bucket, then fill in ascending triangle order.
  start.assign(size_t(columns) * size_t(rows) + 1, 0);
  for (Eigen::Index f = 0; f < m; ++f) {
    if (boxes[size_t(f)].isEmpty()) continue;
    const Eigen::Array4i r = range(boxes[size_t(f)]);
    for (int y = r(2); y <= r(3); ++y)
      for (int x = r(0); x <= r(1); ++x) ++start[size_t(y) * size_t(columns) + size_t(x) + 1];
  }
  for (size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
  triangles.resize(size_t(start.back()));
  std::vector<int> next(start.begin(), start.end() - 1);
  for (Eigen::Index f = 0; f < m; ++f) {
    if (boxes[size_t(f)].isEmpty()) continue;
    const Eigen::Array4i r = range(boxes[size_t(f)]);
    for (int y = r(2); y <= r(3); ++y)
      for (int x = r(0); x <= r(1); ++x)
        triangles[size_t(next[size_t(y) * size_t(columns) + size_t(x)]++)] = int(f);
  }
}

Hit SideIndex::locate(const Eigen::Vector2d& p) const {
  const double x = (p.x() - origin.x()) * inverse_side, y = (p.y() - origin.y()) * inverse_side;
  if (!(x >= 0 && y >= 0 && x < columns && y < rows)) return {};
  const size_t bucket = size_t(int(y)) * size_t(columns) + size_t(int(x));
  for (int k = start[bucket]; k < start[bucket + 1]; ++k) {
    const int f = triangles[size_t(k)];
    const Locator& t = locators[size_t(f)];
    const Eigen::Vector2d l = t.inverse * (p - t.a);
    if (std::min({l.x(), l.y(), 1 - l.x() - l.y()}) >= -WarpMap::kEdgeTolerance)
      return {f, l.x(), l.y()};
  }
  return {};
}

// The point at barycentric (1 - l1 - l2, l1, l2) of triangle `hit.f` on the side V.
Eigen::Vector2d interpolate(const Eigen::MatrixX3i& F, const Eigen::MatrixX2d& V, const Hit& hit) {
  const Eigen::Vector2d a = V.row(F(hit.f, 0)), b = V.row(F(hit.f, 1)), c = V.row(F(hit.f, 2));
  return a + hit.l1 * (b - a) + hit.l2 * (c - a);
}

void require_finite(const Eigen::Vector2d& p, const char* function) {
  if (!p.allFinite())
    require(
        false, function,
        "the point (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ") is not finite");
}

// A row of NaNs, what a batch returns for a point in no triangle, goes through as such, so a
// forward batch chains into an inverse one; any other non-finite row is refused.
void require_finite_rows(const Eigen::MatrixX2d& points, const char* function) {
  if (points.allFinite()) return;
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    require(points.row(i).allFinite() || points.row(i).array().isNaN().all(), function,
            "points row " + std::to_string(i) + " = (" + std::to_string(points(i, 0)) + ", " +
                std::to_string(points(i, 1)) + ") is neither finite nor a row of NaNs");
}

WarpMesh validated(WarpMesh mesh) {
  const char* fn = "WarpMap";
  require(mesh.F.rows() > 0, fn, "the mesh has no triangles");
  require(mesh.source.rows() == mesh.screen.rows(), fn,
          "mesh.source has " + std::to_string(mesh.source.rows()) + " rows but mesh.screen has " +
              std::to_string(mesh.screen.rows()));
  const Eigen::Index vertices = mesh.source.rows();
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (mesh.F(f, k) < 0 || mesh.F(f, k) >= vertices)
        require(false, fn,
                "mesh.F(" + std::to_string(f) + ", " + std::to_string(k) +
                    ") = " + std::to_string(mesh.F(f, k)) + " is not a vertex index in [0, " +
                    std::to_string(vertices) + ")");
  for (const Eigen::MatrixX2d* V : {&mesh.source, &mesh.screen})
    for (Eigen::Index v = 0; v < vertices; ++v)
      if (!V->row(v).allFinite())
        require(false, fn,
                std::string(V == &mesh.source ? "mesh.source" : "mesh.screen") + " row " +
                    std::to_string(v) + " is not finite");
  return mesh;
}

}  // namespace

struct WarpMap::Impl {
  explicit Impl(WarpMesh m)
      : mesh(validated(std::move(m))), source(mesh.F, mesh.source), screen(mesh.F, mesh.screen) {}

  // Maps every row of `points` from the side `from` to the side V, NaN rows where none holds it.
  Eigen::MatrixX2d map(const SideIndex& from, const Eigen::MatrixX2d& V,
                       const Eigen::MatrixX2d& points) const {
    Eigen::MatrixX2d out(points.rows(), 2);
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      if (!points.row(i).allFinite()) {  // a row of NaNs (require_finite_rows)
        out.row(i).setConstant(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      const Hit hit = from.locate(points.row(i).transpose());
      if (hit.f < 0)
        out.row(i).setConstant(std::numeric_limits<double>::quiet_NaN());
      else
        out.row(i) = interpolate(mesh.F, V, hit).transpose();
    }
    return out;
  }

  WarpMesh mesh;
  SideIndex source, screen;
};

WarpMap::WarpMap(WarpMesh mesh) : impl_(std::make_shared<const Impl>(std::move(mesh))) {}

std::optional<Eigen::Vector2d> WarpMap::forward(const Eigen::Vector2d& p) const {
  require_finite(p, "WarpMap::forward");
  const Hit hit = impl_->source.locate(p);
  if (hit.f < 0) return std::nullopt;
  return interpolate(impl_->mesh.F, impl_->mesh.screen, hit);
}

std::optional<Eigen::Vector2d> WarpMap::inverse(const Eigen::Vector2d& q) const {
  require_finite(q, "WarpMap::inverse");
  const Hit hit = impl_->screen.locate(q);
  if (hit.f < 0) return std::nullopt;
  return interpolate(impl_->mesh.F, impl_->mesh.source, hit);
}

Eigen::MatrixX2d WarpMap::forward_batch(const Eigen::MatrixX2d& points) const {
  require_finite_rows(points, "WarpMap::forward_batch");
  return impl_->map(impl_->source, impl_->mesh.screen, points);
}

Eigen::MatrixX2d WarpMap::inverse_batch(const Eigen::MatrixX2d& points) const {
  require_finite_rows(points, "WarpMap::inverse_batch");
  return impl_->map(impl_->screen, impl_->mesh.source, points);
}

Eigen::Index WarpMap::source_triangle(const Eigen::Vector2d& p) const {
  require_finite(p, "WarpMap::source_triangle");
  return impl_->source.locate(p).f;
}

Eigen::Index WarpMap::screen_triangle(const Eigen::Vector2d& q) const {
  require_finite(q, "WarpMap::screen_triangle");
  return impl_->screen.locate(q).f;
}

const WarpMesh& WarpMap::mesh() const { return impl_->mesh; }

WarpMap framed_warp_map(const WarpMesh& warp, int width, int height) {
  require(warp.screen_width > 0 && warp.screen_height > 0 && width > 0 && height > 0,
          "framed_warp_map", "the warp's frame and the output size must be positive");
  WarpMesh framed = warp;
  framed.screen.col(0) *= double(width) / warp.screen_width;
  framed.screen.col(1) *= double(height) / warp.screen_height;
  framed.screen_width = width;
  framed.screen_height = height;
  return WarpMap(std::move(framed));
}

}  // namespace geolens
