#include "geometry/polygon.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "geolens/core/errors.h"
#include "geolens/core/parse.h"
#include "geolens/io/file_io.h"

namespace geolens {
namespace {

std::string point(const Eigen::Vector2d& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ")";
  return s.str();
}

/// (b - a) x (c - a): > 0 when c lies to the left of a -> b.
double orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

/// For c collinear with a and b: whether it lies on the segment a-b.
bool within(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return c.x() >= std::min(a.x(), b.x()) && c.x() <= std::max(a.x(), b.x()) &&
         c.y() >= std::min(a.y(), b.y()) && c.y() <= std::max(a.y(), b.y());
}

/// Whether the closed segments a-b and c-d have a point in common.
bool segments_meet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  const double o1 = orientation(c, d, a), o2 = orientation(c, d, b);
  const double o3 = orientation(a, b, c), o4 = orientation(a, b, d);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) {
    return true;
  }
  return (o1 == 0 && within(c, d, a)) || (o2 == 0 && within(c, d, b)) ||
         (o3 == 0 && within(a, b, c)) || (o4 == 0 && within(a, b, d));
}

/// The crossing rule shared by contains and rasterize_polygon: whether edge a-b crosses the
/// horizontal line at height y (one end above it, the other on or below it), and where.
bool crosses(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double y, double* x) {
  if ((a.y() > y) == (b.y() > y)) return false;
  *x = a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
  return true;
}

}  // namespace

double segment_squared_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).squaredNorm();
}

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
  return std::sqrt(segment_squared_distance(p, a, b));
}

void validate_polygon(const std::vector<Eigen::Vector2d>& vertices, const char* function) {
  const size_t n = vertices.size();
  require(n >= 3, function, "a polygon needs at least 3 vertices, got " + std::to_string(n));
  for (size_t i = 0; i < n; ++i) {
    require(vertices[i].allFinite(), function,
            "vertex " + std::to_string(i) + " " + point(vertices[i]) + " is not finite");
  }
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    require(vertices[i] != vertices[j], function,
            "vertices " + std::to_string(i) + " and " + std::to_string(j) + " coincide at " +
                point(vertices[i]));
  }
  double twice_area = 0;
  Eigen::Vector2d low = vertices[0], high = vertices[0];
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = vertices[i];
    const Eigen::Vector2d& b = vertices[(i + 1) % n];
    twice_area += a.x() * b.y() - a.y() * b.x();
    low = low.cwiseMin(a);
    high = high.cwiseMax(a);
  }
  require(std::abs(twice_area) > 1e-12 * (high - low).squaredNorm(), function,
          "the polygon has zero area");
  // The first pair of edges (i, then j > i, smallest) that meet other than at the vertex
  // consecutive edges share. Only edges sharing a cell of a grid of about n cells over the
  // bounding box can meet, so a polygon of 100 000 vertices is checked in well under a second
  // (every pair: 45 s).
  auto meet = [&](size_t i, size_t j) {
    const Eigen::Vector2d &a = vertices[i], &b = vertices[(i + 1) % n];
    const Eigen::Vector2d &c = vertices[j], &d = vertices[(j + 1) % n];
    if (j == i + 1)  // consecutive, sharing b = c: they overlap when d folds back along a-b
      return orientation(a, b, d) == 0 && (a - b).dot(d - b) > 0;
    if (i == 0 && j == n - 1)  // consecutive, sharing a = d
      return orientation(a, b, c) == 0 && (b - a).dot(c - a) > 0;
    return segments_meet(a, b, c, d);
  };
  const Eigen::Vector2d size = (high - low).cwiseMax(1e-300);
  const int side = int(std::clamp(std::sqrt(double(n)), 1.0, 2048.0));
  const Eigen::Vector2d cell = size / side;
  auto cell_of = [&](double v, int axis) {
    return std::clamp(int((v - low[axis]) / cell[axis]), 0, side - 1);
  };
  std::vector<std::vector<size_t>> cells(size_t(side) * size_t(side));
  std::vector<std::array<int, 4>> spans(n);  // per edge: its cells' x0, x1, y0, y1
  for (size_t e = 0; e < n; ++e) {
    const Eigen::Vector2d &a = vertices[e], &b = vertices[(e + 1) % n];
    spans[e] = {cell_of(std::min(a.x(), b.x()), 0), cell_of(std::max(a.x(), b.x()), 0),
                cell_of(std::min(a.y(), b.y()), 1), cell_of(std::max(a.y(), b.y()), 1)};
    for (int y = spans[e][2]; y <= spans[e][3]; ++y)
      for (int x = spans[e][0]; x <= spans[e][1]; ++x)
        cells[size_t(y) * size_t(side) + size_t(x)].push_back(e);
  }
  size_t first = n, second = n;
  for (size_t i = 0; i < n && first == n; ++i) {
    for (int y = spans[i][2]; y <= spans[i][3]; ++y)
      for (int x = spans[i][0]; x <= spans[i][1]; ++x)
        for (const size_t j : cells[size_t(y) * size_t(side) + size_t(x)])
          if (j > i && j < second && meet(i, j)) {
            first = i;
            second = j;
          }
  }
  auto edge = [&](size_t e) {
    return "edge " + std::to_string(e) + " " + point(vertices[e]) + "-" +
           point(vertices[(e + 1) % n]);
  };
  require(first == n, function,
          first == n ? std::string() : edge(first) + " and " + edge(second) + " intersect");
}

std::vector<Eigen::Vector2d> simplify_loop(const std::vector<Eigen::Vector2d>& loop,
                                           double tolerance) {
  const size_t n = loop.size();
  if (n < 3) return loop;
  size_t far = 0;
  for (size_t k = 1; k < n; ++k)
    if ((loop[k] - loop[0]).squaredNorm() > (loop[far] - loop[0]).squaredNorm()) far = k;
  std::vector<char> keep(n, 0);
  keep[0] = keep[far] = 1;
  // Spans (first, last) of indices modulo n between two kept points, still to split.
  std::vector<std::pair<size_t, size_t>> spans = {{0, far}, {far, n}};
  while (!spans.empty()) {
    const auto [first, last] = spans.back();
    spans.pop_back();
    double worst = -1;
    size_t at = first;
    for (size_t k = first + 1; k < last; ++k) {
      const double d = segment_distance(loop[k % n], loop[first % n], loop[last % n]);
      if (d > worst) {
        worst = d;
        at = k;
      }
    }
    if (worst <= tolerance) continue;
    keep[at % n] = 1;
    spans.emplace_back(at, last);
    spans.emplace_back(first, at);
  }
  std::vector<Eigen::Vector2d> out;
  for (size_t k = 0; k < n; ++k)
    if (keep[k]) out.push_back(loop[k]);
  return out;
}

std::vector<Eigen::Vector2d> read_polygon_file(const std::string& path) {
  constexpr size_t kMaxPolygonBytes = size_t(64) << 20;  // a few million vertices
  std::istringstream in(read_file(path, "read_polygon_file", "polygon", kMaxPolygonBytes));
  std::vector<Eigen::Vector2d> vertices;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::string content = line.substr(0, line.find('#'));
    std::replace_if(
        content.begin(), content.end(), [](char c) { return c == ',' || c == ';'; }, ' ');
    std::istringstream tokens(content);
    std::vector<std::string> words;
    for (std::string word; tokens >> word;) words.push_back(word);
    if (words.empty()) continue;
    Eigen::Vector2d v;
    bool ok = words.size() == 2;
    for (int k = 0; ok && k < 2; ++k) {
      const std::string& w = words[size_t(k)];
      const std::optional<double> read = read_number(w);  // finite, all of w (core/parse.h)
      ok = read.has_value();
      if (ok) v[k] = *read;
    }
    require(ok, "read_polygon_file",
            path + ":" + std::to_string(number) + ": expected two finite numbers \"x y\", got \"" +
                quoted_line(line) + "\"");
    vertices.push_back(v);
  }
  if (vertices.size() > 1 && vertices.back() == vertices.front()) vertices.pop_back();
  return vertices;
}

std::vector<uint8_t> rasterize_polygon(const std::vector<Eigen::Vector2d>& vertices, int width,
                                       int height, const Eigen::Vector2d& origin, double cell) {
  require(width > 0 && height > 0, "rasterize_polygon",
          "raster size must be positive, got " + std::to_string(width) + " x " +
              std::to_string(height));
  require(origin.allFinite() && std::isfinite(cell) && cell > 0, "rasterize_polygon",
          "origin must be finite and cell positive, got cell " + std::to_string(cell));
  const size_t n = vertices.size();
  std::vector<uint8_t> inside(size_t(width) * height, 0);
  std::vector<double> xs;
  for (int j = 0; j < height; ++j) {
    const double y = origin.y() + cell * j;
    xs.clear();
    for (size_t e = 0; e < n; ++e) {
      double x;
      if (crosses(vertices[e], vertices[(e + 1) % n], y, &x)) xs.push_back(x);
    }
    std::sort(xs.begin(), xs.end());
    // A node is inside when an odd number of crossings lie strictly to its right, i.e. (their
    // count being even) an odd number lie at or to its left.
    size_t left = 0;
    for (int i = 0; i < width; ++i) {
      const double x = origin.x() + cell * i;
      while (left < xs.size() && xs[left] <= x) ++left;
      inside[size_t(j) * width + i] = uint8_t(left % 2);
    }
  }
  return inside;
}

PolygonIndex::PolygonIndex(std::vector<Eigen::Vector2d> vertices, double band)
    : vertices_(std::move(vertices)), band_(band) {
  require(vertices_.size() >= 3, "PolygonIndex",
          "a polygon needs at least 3 vertices, got " + std::to_string(vertices_.size()));
  require(std::isfinite(band) && band > 0, "PolygonIndex",
          "band must be a positive number, got " + std::to_string(band));
  const size_t n = vertices_.size();
  bottom_ = vertices_[0].y();
  double top = bottom_;
  for (const Eigen::Vector2d& v : vertices_) {
    bottom_ = std::min(bottom_, v.y());
    top = std::max(top, v.y());
  }
  const int bands = int((top - bottom_) / band_) + 1;
  auto band_of = [&](double y) { return std::clamp(int((y - bottom_) / band_), 0, bands - 1); };
  first_.assign(size_t(bands) + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> fill(first_.begin(), first_.end() - 1);
    for (size_t e = 0; e < n; ++e) {
      const double y0 = vertices_[e].y(), y1 = vertices_[(e + 1) % n].y();
      for (int k = band_of(std::min(y0, y1)); k <= band_of(std::max(y0, y1)); ++k) {
        if (pass == 0) {
          ++first_[size_t(k) + 1];
        } else {
          edges_[size_t(fill[size_t(k)]++)] = int(e);
        }
      }
    }
    if (pass == 0) {
      for (int k = 0; k < bands; ++k) first_[size_t(k) + 1] += first_[size_t(k)];
      edges_.resize(size_t(first_.back()));
    }
  }
}

bool PolygonIndex::contains(const Eigen::Vector2d& p) const {
  const int bands = int(first_.size()) - 1;
  const double y = p.y() - bottom_;
  if (!(y >= 0 && y <= bands * band_)) return false;
  const int k = std::min(int(y / band_), bands - 1);
  const size_t n = vertices_.size();
  bool inside = false;
  for (int i = first_[size_t(k)]; i < first_[size_t(k) + 1]; ++i) {
    const size_t e = size_t(edges_[size_t(i)]);
    double x;
    if (crosses(vertices_[e], vertices_[(e + 1) % n], p.y(), &x) && x > p.x()) inside = !inside;
  }
  return inside;
}

double PolygonIndex::boundary_distance(const Eigen::Vector2d& p, double reach) const {
  const int bands = int(first_.size()) - 1;
  const double low = (p.y() - reach - bottom_) / band_, high = (p.y() + reach - bottom_) / band_;
  if (!(high >= 0 && low < bands)) return reach;
  const int k0 = int(std::max(low, 0.0)), k1 = int(std::min(high, bands - 1.0));
  const size_t n = vertices_.size();
  double best = reach;
  for (int i = first_[size_t(k0)]; i < first_[size_t(k1) + 1]; ++i) {
    const size_t e = size_t(edges_[size_t(i)]);
    const Eigen::Vector2d& a = vertices_[e];
    const Eigen::Vector2d& b = vertices_[(e + 1) % n];
    if (std::min(a.x(), b.x()) - p.x() >= best || p.x() - std::max(a.x(), b.x()) >= best) continue;
    best = std::min(best, segment_distance(p, a, b));
  }
  return best;
}

}  // namespace geolens
