#include "source/map_labels.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

#include "geolens/core/errors.h"
#include "source/cairo_tile.h"

namespace geolens {

namespace {

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

constexpr const char* kFont = "sans-serif";

/// sqrt |det J| of the warp on the source triangle holding p, or 0 if none does.
double local_scale(const WarpMap& map, const Eigen::Vector2d& p) {
  const Eigen::Index t = map.source_triangle(p);
  if (t < 0) return 0;
  const WarpMesh& mesh = map.mesh();
  const Eigen::Vector3i f = mesh.F.row(t);
  auto edge_cross = [&](const Eigen::MatrixX2d& v) {
    const Eigen::Vector2d a = (v.row(f[1]) - v.row(f[0])).transpose();
    const Eigen::Vector2d b = (v.row(f[2]) - v.row(f[0])).transpose();
    return a.x() * b.y() - a.y() * b.x();
  };
  // The Jacobian's determinant: the ratio of the triangle's screen and source areas.
  const double det_source = edge_cross(mesh.source);
  if (det_source == 0) return 0;
  return std::sqrt(std::abs(edge_cross(mesh.screen) / det_source));
}

void set_color(cairo_t* cr, const MapColor& c) { cairo_set_source_rgba(cr, c.r, c.g, c.b, c.a); }

bool overlaps(const PlacedLabel& a, const PlacedLabel& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

}  // namespace

std::vector<PlacedLabel> place_labels(const std::vector<MapLabel>& labels, const WarpMap& map,
                                      int width, int height) {
  std::vector<size_t> order(labels.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return labels[a].rank < labels[b].rank; });

  // A context of its own to measure text with.
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_A8, 1, 1), &cairo_surface_destroy);
  ContextPtr cr(cairo_create(surface.get()), &cairo_destroy);
  cairo_select_font_face(cr.get(), kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);

  std::vector<PlacedLabel> placed;
  for (size_t i : order) {
    const MapLabel& label = labels[i];
    if (label.text.empty() || !label.position.allFinite()) continue;
    const std::optional<Eigen::Vector2d> anchor = map.forward(label.position);
    if (!anchor) continue;
    const double scale = local_scale(map, label.position);
    if (!(scale > 0) || scale < std::exp2(label.rank - label.style.base) ||
        scale < label.min_zoom || scale >= label.max_zoom)
      continue;

    cairo_set_font_size(cr.get(), label.style.size);
    cairo_text_extents_t e;
    cairo_text_extents(cr.get(), label.text.c_str(), &e);
    require(
        cairo_status(cr.get()) == CAIRO_STATUS_SUCCESS, "place_labels",
        "cannot measure '" + label.text + "': " + cairo_status_to_string(cairo_status(cr.get())));
    const double margin = label.style.halo_width + 0.5, gap = label.offset;
    const double ax = anchor->x(), ay = anchor->y();
    // The text's origin on each side of the point, its ink box centred on that side.
    const double centre_x = -e.x_bearing - e.width / 2, centre_y = -e.y_bearing - e.height / 2;
    const double sides[4][2] = {
        {ax + gap + margin - e.x_bearing, ay + centre_y},
        {ax - gap - margin - e.width - e.x_bearing, ay + centre_y},
        {ax + centre_x, ay - gap - margin - e.height - e.y_bearing},
        {ax + centre_x, ay + gap + margin - e.y_bearing},
    };
    for (const auto& side : sides) {
      PlacedLabel p;
      p.index = i;
      p.anchor = *anchor;
      p.scale = scale;
      p.text_x = side[0];
      p.text_y = side[1];
      p.x0 = side[0] + e.x_bearing - margin;
      p.y0 = side[1] + e.y_bearing - margin;
      p.x1 = p.x0 + e.width + 2 * margin;
      p.y1 = p.y0 + e.height + 2 * margin;
      if (p.x0 < 0 || p.y0 < 0 || p.x1 > width || p.y1 > height) continue;
      if (std::any_of(placed.begin(), placed.end(),
                      [&](const PlacedLabel& q) { return overlaps(p, q); }))
        continue;
      placed.push_back(p);
      break;
    }
  }
  return placed;
}

void draw_dots(Image& image, const std::vector<MapDot>& dots, const WarpMap& map) {
  require(image.channels == 3 || image.channels == 4, "draw_dots",
          "the image must be RGB or RGBA, got " + std::to_string(image.channels) + " channels");
  if (dots.empty()) return;
  SurfacePtr surface(image_to_cairo(image), &cairo_surface_destroy);
  ContextPtr cr(cairo_create(surface.get()), &cairo_destroy);
  for (const MapDot& dot : dots) {
    if (!dot.position.allFinite() || !(dot.radius > 0) || (!dot.fill && !dot.stroke)) continue;
    const std::optional<Eigen::Vector2d> at = map.forward(dot.position);
    if (!at) continue;
    const double scale = local_scale(map, dot.position);
    if (scale < dot.min_zoom || scale >= dot.max_zoom) continue;
    cairo_new_path(cr.get());
    cairo_arc(cr.get(), at->x(), at->y(), dot.radius, 0, 2 * 3.14159265358979323846);
    if (dot.fill) {
      set_color(cr.get(), *dot.fill);
      cairo_fill_preserve(cr.get());
    }
    if (dot.stroke && dot.width > 0) {
      set_color(cr.get(), *dot.stroke);
      cairo_set_line_width(cr.get(), dot.width);
      cairo_stroke_preserve(cr.get());
    }
    cairo_new_path(cr.get());
  }
  require(cairo_status(cr.get()) == CAIRO_STATUS_SUCCESS, "draw_dots",
          std::string("cairo: ") + cairo_status_to_string(cairo_status(cr.get())));
  cairo_to_image(surface.get(), image);
}

void draw_labels(Image& image, const std::vector<MapLabel>& labels,
                 const std::vector<PlacedLabel>& placed) {
  require(image.channels == 3 || image.channels == 4, "draw_labels",
          "the image must be RGB or RGBA, got " + std::to_string(image.channels) + " channels");
  if (placed.empty()) return;
  SurfacePtr surface(image_to_cairo(image), &cairo_surface_destroy);
  ContextPtr cr(cairo_create(surface.get()), &cairo_destroy);
  cairo_select_font_face(cr.get(), kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_line_join(cr.get(), CAIRO_LINE_JOIN_ROUND);
  for (const PlacedLabel& p : placed) {
    require(p.index < labels.size(), "draw_labels", "a placed label's index is out of range");
    const MapLabel& label = labels[p.index];
    cairo_set_font_size(cr.get(), label.style.size);
    cairo_new_path(cr.get());
    cairo_move_to(cr.get(), p.text_x, p.text_y);
    cairo_text_path(cr.get(), label.text.c_str());
    if (label.style.halo_width > 0) {
      set_color(cr.get(), label.style.halo);
      cairo_set_line_width(cr.get(), 2 * label.style.halo_width);
      cairo_stroke_preserve(cr.get());
    }
    set_color(cr.get(), label.style.color);
    cairo_fill(cr.get());
  }
  require(cairo_status(cr.get()) == CAIRO_STATUS_SUCCESS, "draw_labels",
          std::string("cairo: ") + cairo_status_to_string(cairo_status(cr.get())));
  cairo_to_image(surface.get(), image);
}

}  // namespace geolens
