#include "lens/framing.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace geolens {

Eigen::MatrixX2d frame(const Eigen::MatrixX2d& X, Boundary boundary, double width, double height) {
  if (boundary != Boundary::kFree) return X;
  const Eigen::Vector2d lo = X.colwise().minCoeff(), hi = X.colwise().maxCoeff();
  const Eigen::Vector2d extent = hi - lo;
  const double scale = std::min(width / extent.x(), height / extent.y());
  const Eigen::RowVector2d offset(0.5 * (width - scale * extent.x()),
                                  0.5 * (height - scale * extent.y()));
  return ((X.rowwise() - lo.transpose()) * scale).rowwise() + offset;
}

void add_identity_frame(WarpMesh& warp, const PlanarMesh& mesh, const Eigen::AlignedBox2d& box,
                        double width, double height) {
  const Eigen::Vector2d lo = box.min(), hi = box.max();
  // The four image corners are appended as identity vertices.
  const Eigen::Index first = warp.source.rows();
  const Eigen::Vector2d corner[4] = {{0, 0}, {width, 0}, {width, height}, {0, height}};
  warp.source.conservativeResize(first + 4, 2);
  warp.screen.conservativeResize(first + 4, 2);
  for (int k = 0; k < 4; ++k) {
    warp.source.row(first + k) = corner[k].transpose();
    warp.screen.row(first + k) = corner[k].transpose();
  }
  std::vector<Eigen::RowVector3i> faces;
  // Side k runs from patch corner k to k + 1 (top: left to right, right: top to bottom, ...),
  // facing image corners k and k + 1.
  const Eigen::Vector2d patch_corner[4] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d a = patch_corner[k], b = patch_corner[(k + 1) % 4];
    const Eigen::Vector2d direction = (b - a).normalized();
    // The trapezoid is empty where the patch touches the image side.
    const Eigen::Vector2d outward(direction.y(), -direction.x());
    if (std::abs((corner[k] - a).dot(outward)) < 1e-9) continue;
    std::vector<std::pair<double, int>> side;
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
      if (mesh.sides[size_t(i)] == 0) continue;
      const Eigen::Vector2d p = mesh.V.row(i);
      const Eigen::Vector2d d = p - a;
      if (std::abs(d.dot(outward)) < 1e-9 && d.dot(direction) > -1e-9 &&
          d.dot(direction) < (b - a).norm() + 1e-9)
        side.emplace_back(d.dot(direction), int(i));
    }
    std::sort(side.begin(), side.end());
    const int ca = int(first) + k, cb = int(first) + (k + 1) % 4;
    const size_t middle = side.size() / 2;
    // With y down, image corner -> patch side -> ... is oriented like the grid's triangles
    // when the patch side is walked from b back to a.
    for (size_t i = 0; i + 1 < side.size(); ++i) {
      const int apex = i < middle ? ca : cb;
      faces.emplace_back(apex, side[i + 1].second, side[i].second);
    }
    faces.emplace_back(ca, cb, side[middle].second);
  }
  const Eigen::Index old = warp.F.rows();
  warp.F.conservativeResize(old + Eigen::Index(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) warp.F.row(old + Eigen::Index(f)) = faces[f];
}

}  // namespace geolens
