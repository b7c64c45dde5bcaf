#include "geometry/distance_field.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <string>

#include "geolens/core/errors.h"

namespace geolens {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Axis criterion (see medial_axis in the header).
constexpr double kSlack = 1.5;  // cells
const double kMinAngle = 50.0 * std::numbers::pi / 180.0;
const double kDepthPerRadius = std::pow(std::sin(0.5 * kMinAngle), 2);

void require_size(size_t size, int width, int height, const char* function) {
  require(width > 0 && height > 0, function,
          "raster size must be positive, got " + std::to_string(width) + " x " +
              std::to_string(height));
  require(size == size_t(width) * size_t(height), function,
          "expected " + std::to_string(size_t(width) * size_t(height)) + " nodes for " +
              std::to_string(width) + " x " + std::to_string(height) + ", got " +
              std::to_string(size));
}

/// One dimension of Felzenszwalb & Huttenlocher (2012), algorithm DT(f): the lower envelope of
/// the parabolas (x - q)^2 + f[q] over the finite f[q], q in [0, n). Writes d[x] = min over q
/// and arg[x] = the minimizing q (-1 when every f is infinite). `v` (n) and `z` (n + 1) are
/// scratch: the envelope's parabolas and the boundaries between them.
void envelope(const double* f, int n, double* d, int* arg, int* v, double* z) {
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[q] == kInfinity) continue;
    const double fq = f[q] + double(q) * q;
    double s = -kInfinity;
    while (k >= 0) {
      s = (fq - (f[v[k]] + double(v[k]) * v[k])) / (2.0 * (q - v[k]));
      if (s > z[k]) break;
      --k;
    }
    ++k;
    v[k] = q;
    z[k] = k == 0 ? -kInfinity : s;
    z[k + 1] = kInfinity;
  }
  if (k < 0) {
    std::fill(d, d + n, kInfinity);
    std::fill(arg, arg + n, -1);
    return;
  }
  k = 0;
  for (int x = 0; x < n; ++x) {
    while (z[k + 1] < x) ++k;
    d[x] = double(x - v[k]) * (x - v[k]) + f[v[k]];
    arg[x] = v[k];
  }
}

/// Bilinear sample of a node field at raster coordinates (u, v); 0 outside the raster.
double bilinear(const std::vector<float>& field, int width, int height, double u, double v) {
  if (!(u >= 0 && v >= 0 && u <= width - 1 && v <= height - 1)) return 0;
  const int i = std::min(int(u), width - 2), j = std::min(int(v), height - 2);
  const double s = u - i, t = v - j;
  const float* row = field.data() + size_t(j) * width + i;
  return (1 - t) * ((1 - s) * row[0] + s * row[1]) +
         t * ((1 - s) * row[width] + s * row[width + 1]);
}

}  // namespace

DistanceTransform distance_transform(const std::vector<uint8_t>& sites, int width, int height) {
  require_size(sites.size(), width, height, "distance_transform");
  const size_t count = size_t(width) * height;
  // Columns: the row of the nearest site in the same column (-1 if none), the 1D transform of a
  // binary column, by a downward sweep (nearest site above) and an upward one (nearer below?)
  // over whole rows, which keeps the memory access sequential.
  std::vector<int> column_row(count, -1);
  for (int y = 0; y < height; ++y) {
    const size_t row = size_t(y) * width;
    for (int x = 0; x < width; ++x) {
      column_row[row + x] = sites[row + x] ? y : y > 0 ? column_row[row - width + x] : -1;
    }
  }
  std::vector<double> column_squared(count);
  for (int y = height - 1; y >= 0; --y) {
    const size_t row = size_t(y) * width;
    for (int x = 0; x < width; ++x) {
      int& nearest = column_row[row + x];
      const int below = y + 1 < height ? column_row[row + width + x] : -1;
      if (below >= 0 && (nearest < 0 || std::abs(below - y) < y - nearest)) nearest = below;
      column_squared[row + x] = nearest < 0 ? kInfinity : double(y - nearest) * (y - nearest);
    }
  }
  const size_t n = size_t(width);
  std::vector<double> z(n + 1);
  std::vector<int> arg(n), v(n);
  // Rows: the nearest of the column minima.
  DistanceTransform out;
  out.squared.resize(count);
  out.nearest.resize(count);
  for (int y = 0; y < height; ++y) {
    const size_t row = size_t(y) * width;
    envelope(column_squared.data() + row, width, out.squared.data() + row, arg.data(), v.data(),
             z.data());
    for (int x = 0; x < width; ++x) {
      const int q = arg[size_t(x)];
      out.nearest[row + x] = q < 0 ? -1 : column_row[row + q] * width + q;
    }
  }
  return out;
}

std::vector<uint8_t> medial_axis(const std::vector<uint8_t>& inside, int width, int height,
                                 const DistanceTransform& outside) {
  require_size(inside.size(), width, height, "medial_axis");
  require(outside.squared.size() == inside.size() && outside.nearest.size() == inside.size(),
          "medial_axis", "the distance transform does not match the raster size");
  std::vector<uint8_t> axis(inside.size(), 0);
  auto position = [width](int index) { return Eigen::Vector2d(index % width, index / width); };
  int deepest = -1;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int p = y * width + x;
      if (!inside[size_t(p)] || outside.nearest[size_t(p)] < 0) continue;
      if (deepest < 0 || outside.squared[size_t(p)] > outside.squared[size_t(deepest)]) {
        deepest = p;
      }
      for (const int q : {x + 1 < width ? p + 1 : -1, y + 1 < height ? p + width : -1}) {
        if (q < 0 || !inside[size_t(q)]) continue;
        const int fp = outside.nearest[size_t(p)], fq = outside.nearest[size_t(q)];
        if (fp == fq || fq < 0) continue;
        const Eigen::Vector2d P = position(p), Q = position(q), Fp = position(fp),
                              Fq = position(fq);
        const Eigen::Vector2d m = 0.5 * (P + Q);
        const double radius = 0.5 * ((Fp - m).norm() + (Fq - m).norm());
        const Eigen::Vector2d c = 0.5 * (Fp + Fq);
        const double chord_depth =
            std::sqrt(outside.squared[size_t(std::lround(c.y())) * width + std::lround(c.x())]);
        if (chord_depth - kSlack < kDepthPerRadius * radius) continue;
        // (P - Fq)^2 - (P - Fp)^2 is affine in P: it measures how far P is from the bisector.
        const double sp = (P - Fq).squaredNorm() - (P - Fp).squaredNorm();
        const double sq = (Q - Fp).squaredNorm() - (Q - Fq).squaredNorm();
        if (sp <= sq) axis[size_t(p)] = 1;
        if (sq <= sp) axis[size_t(q)] = 1;
      }
    }
  }
  if (deepest >= 0) axis[size_t(deepest)] = 1;
  return axis;
}

double DepthRaster::boundary_distance(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d uv = (p - origin) / cell;
  return std::max(0.0, bilinear(boundary, width, height, uv.x(), uv.y()));
}

double DepthRaster::axis_distance(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d uv = (p - origin) / cell;
  return bilinear(axis, width, height, uv.x(), uv.y());
}

DepthRaster depth_raster(const std::vector<uint8_t>& inside, int width, int height,
                         const Eigen::Vector2d& origin, double cell) {
  require_size(inside.size(), width, height, "depth_raster");
  require(origin.allFinite(), "depth_raster", "origin is not finite");
  require(std::isfinite(cell) && cell > 0, "depth_raster",
          "cell must be a positive number, got " + std::to_string(cell));
  bool any = false;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (!inside[size_t(y) * width + x]) continue;
      any = true;
      // Not require(): its message would be built for every inside node (15 % of a star's frame).
      if (x == 0 || y == 0 || x + 1 == width || y + 1 == height)
        throw InvalidInput("depth_raster: inside node (" + std::to_string(x) + ", " +
                           std::to_string(y) + ") lies on the raster border; pad the raster");
    }
  }
  require(any, "depth_raster", "no node is inside");

  std::vector<uint8_t> outside_sites(inside.size());
  std::transform(inside.begin(), inside.end(), outside_sites.begin(),
                 [](uint8_t v) { return uint8_t(v == 0); });
  const DistanceTransform outside = distance_transform(outside_sites, width, height);
  const std::vector<uint8_t> axis = medial_axis(inside, width, height, outside);
  const DistanceTransform to_axis = distance_transform(axis, width, height);

  DepthRaster r;
  r.width = width;
  r.height = height;
  r.origin = origin;
  r.cell = cell;
  r.boundary.resize(inside.size());
  r.axis.resize(inside.size());
  double deepest = 0;
  for (size_t i = 0; i < inside.size(); ++i) {
    const double b = inside[i] ? cell * (std::sqrt(outside.squared[i]) - 0.5) : -0.5 * cell;
    r.boundary[i] = float(b);
    r.axis[i] = float(cell * std::sqrt(to_axis.squared[i]));
    if (axis[i]) deepest = std::max(deepest, b);
  }
  // The peak: the axis node nearest the centroid of the axis nodes within a cell of the deepest.
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  int near_deepest = 0;
  for (size_t i = 0; i < inside.size(); ++i) {
    if (!axis[i] || r.boundary[i] < deepest - cell) continue;
    centroid += Eigen::Vector2d(double(i % width), double(i / width));
    ++near_deepest;
  }
  centroid /= near_deepest;
  double best = kInfinity;
  for (size_t i = 0; i < inside.size(); ++i) {
    if (!axis[i] || r.boundary[i] < deepest - cell) continue;
    const Eigen::Vector2d node(double(i % width), double(i / width));
    if ((node - centroid).squaredNorm() < best) {
      best = (node - centroid).squaredNorm();
      r.peak = origin + cell * node;
    }
  }
  return r;
}

double depth_from_distances(double a, double b) { return b > 0 ? b / (a + b) : 0.0; }

}  // namespace geolens
