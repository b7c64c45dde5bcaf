#include "geolens/render/overlay.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/io/geojson.h"
#include "geolens/render/annotate.h"
#include "geometry/polygon.h"

namespace geolens {

namespace {

// Draws one path at a time: each pixel keeps the largest coverage any of the path's segments
// gives it, and the path is blended once.
class Stroker {
 public:
  explicit Stroker(Image& image)
      : image_(image), coverage_(size_t(image.width) * size_t(image.height), 0.f) {}

  // A polyline (or a dot: one row) of the given half width, pixels.
  void path(const Eigen::MatrixX2d& P, double half_width, const std::array<uint8_t, 3>& colour) {
    if (P.rows() == 1) segment(P.row(0).transpose(), P.row(0).transpose(), half_width);
    for (Eigen::Index i = 0; i + 1 < P.rows(); ++i)
      segment(P.row(i).transpose(), P.row(i + 1).transpose(), half_width);
    for (const size_t k : touched_) {
      const double alpha = coverage_[k];
      uint8_t* pixel = image_.pixels.data() + k * size_t(image_.channels);
      for (int c = 0; c < 3; ++c)
        pixel[c] = uint8_t(std::lround(pixel[c] + alpha * (colour[size_t(c)] - pixel[c])));
      if (image_.channels == 4)
        pixel[3] = uint8_t(std::lround(pixel[3] + alpha * (255 - pixel[3])));
      coverage_[k] = 0;
    }
    touched_.clear();
  }

 private:
  void segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double half_width) {
    const double reach = half_width + 0.5;
    // The pixels whose centres are within reach of the segment's bounding box, clipped.
    const double x0 = std::max(std::floor(std::min(a.x(), b.x()) - reach), 0.0),
                 x1 = std::min(std::ceil(std::max(a.x(), b.x()) + reach), double(image_.width)),
                 y0 = std::max(std::floor(std::min(a.y(), b.y()) - reach), 0.0),
                 y1 = std::min(std::ceil(std::max(a.y(), b.y()) + reach), double(image_.height));
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = int(x0); x < int(x1); ++x) {
        const double d = segment_distance(Eigen::Vector2d(x + 0.5, y + 0.5), a, b);
        const float c = float(std::clamp(reach - d, 0.0, 1.0));
        float& k = coverage_[size_t(y) * size_t(image_.width) + size_t(x)];
        if (c <= k) continue;
        if (k == 0) touched_.push_back(size_t(y) * size_t(image_.width) + size_t(x));
        k = c;
      }
  }

  Image& image_;
  std::vector<float> coverage_;  // per pixel, 0 outside the current path
  std::vector<size_t> touched_;  // the pixels the current path covers
};

bool is_point(const Geometry& g) {
  return g.type == GeometryType::kPoint || g.type == GeometryType::kMultiPoint;
}

// Every path of g and its members: points (true) or lines and rings (false).
void paths(const Geometry& g, bool points, std::vector<const Eigen::MatrixX2d*>& out) {
  if (g.type == GeometryType::kGeometryCollection) {
    for (const Geometry& m : g.members) paths(m, points, out);
  } else if (is_point(g) == points) {
    for (const Eigen::MatrixX2d& P : g.paths) out.push_back(&P);
  }
}

// The area centroid of a closed ring (its vertex mean if it has no area), pixels.
Eigen::Vector2d centroid(const Eigen::MatrixX2d& ring) {
  double area = 0;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (Eigen::Index i = 0; i + 1 < ring.rows(); ++i) {
    const Eigen::Vector2d a = ring.row(i).transpose(), b = ring.row(i + 1).transpose();
    const double cross = a.x() * b.y() - a.y() * b.x();
    area += cross;
    sum += cross * (a + b);
  }
  if (std::abs(area) > 1e-12) return sum / (3 * area);
  return ring.colwise().mean().transpose();
}

// Where a label goes: the point it is right of (beside) or centred on.
struct Anchor {
  Eigen::Vector2d at;
  bool beside = false;
};

std::optional<Anchor> anchor(const Geometry& g) {
  switch (g.type) {
    case GeometryType::kPoint:
    case GeometryType::kMultiPoint:
      if (g.paths[0].rows() == 0) return std::nullopt;
      return Anchor{g.paths[0].row(0).transpose(), true};
    case GeometryType::kLineString:
    case GeometryType::kMultiLineString:
      if (g.paths.empty()) return std::nullopt;
      return Anchor{g.paths[0].row(g.paths[0].rows() / 2).transpose(), false};
    case GeometryType::kPolygon:
    case GeometryType::kMultiPolygon:
      if (g.paths.empty()) return std::nullopt;
      return Anchor{centroid(g.paths[0]), false};
    case GeometryType::kGeometryCollection:
      for (const Geometry& m : g.members)
        if (const std::optional<Anchor> a = anchor(m)) return a;
      return std::nullopt;
  }
  return std::nullopt;
}

void draw_label(Image& image, const Anchor& anchor, const std::string& text,
                const OverlayStyle& style) {
  const int scale = style.label_scale;
  const Eigen::Vector2d at = anchor.at;
  if (!(at.x() >= 0 && at.y() >= 0 && at.x() < image.width && at.y() < image.height)) return;
  const int width = text_width(text, scale);
  const int x =
      int(std::lround(anchor.beside ? at.x() + style.point_radius + 3 : at.x() - width / 2.0));
  const int y = int(std::lround(at.y() - 3.5 * scale));
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if (dx != 0 || dy != 0) draw_text(image, x + dx, y + dy, text, scale, {255, 255, 255});
  draw_text(image, x, y, text, scale, style.label_colour);
}

}  // namespace

void draw_overlay(Image& image, const VectorData& data, const OverlayStyle& style) {
  const char* fn = "draw_overlay";
  require(image.channels == 3 || image.channels == 4, fn,
          "the image must be RGB or RGBA, it has " + std::to_string(image.channels) + " channels");
  require(std::isfinite(style.line_width) && style.line_width > 0, fn,
          "line_width must be finite and > 0, got " + std::to_string(style.line_width));
  require(std::isfinite(style.point_radius) && style.point_radius > 0, fn,
          "point_radius must be finite and > 0, got " + std::to_string(style.point_radius));
  require(style.label_scale >= 0, fn,
          "label_scale must be >= 0, got " + std::to_string(style.label_scale));
  const std::string problem = vector_data_problem(data);
  require(problem.empty(), fn, problem);

  Stroker stroker(image);
  for (const bool points : {false, true}) {
    std::vector<const Eigen::MatrixX2d*> all;
    for (const Feature& f : data.features)
      if (f.geometry) paths(*f.geometry, points, all);
    for (const Eigen::MatrixX2d* P : all) {
      if (!points) {
        stroker.path(*P, style.line_width / 2, style.line_colour);
        continue;
      }
      for (Eigen::Index i = 0; i < P->rows(); ++i)
        stroker.path(P->row(i), style.point_radius, style.point_colour);
    }
  }
  if (style.label_scale == 0) return;
  for (const Feature& f : data.features) {
    if (!f.geometry) continue;
    const std::optional<std::string> text = string_property(f, style.label_property);
    const std::optional<Anchor> at = anchor(*f.geometry);
    if (text && at) draw_label(image, *at, *text, style);
  }
}

}  // namespace geolens
