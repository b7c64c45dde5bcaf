#pragma once
// Vector features drawn over a picture: points as dots, lines and rings as anti-aliased strokes,
// labels upright.

#include <array>
#include <cstdint>
#include <string>

#include "geolens/io/image.h"
#include "geolens/io/vector_data.h"

namespace geolens {

/// How draw_overlay draws: colours (RGB), stroke and dot sizes in the image's pixels, labels.
struct OverlayStyle {
  std::array<uint8_t, 3> line_colour = {20, 90, 220};   ///< lines and polygon rings
  std::array<uint8_t, 3> point_colour = {225, 35, 35};  ///< dots
  std::array<uint8_t, 3> label_colour = {15, 15, 15};   ///< text, on a white halo
  double line_width = 2.0;                              ///< stroke width, pixels, > 0
  double point_radius = 3.5;                            ///< dot radius, pixels, > 0
  /// Label size in pixels per font unit (annotate.h's stroke font: capitals 7 units tall), >= 0;
  /// 0 draws no labels.
  int label_scale = 2;
  std::string label_property = "name";  ///< the string property a label shows
};

/// Draws `data` over `image`, its coordinates in the image's pixels (pixel (x, y) covers
/// [x, x + 1) x [y, y + 1); typically features mapped with map_features, warp/map_features.h,
/// through the warp the image was rendered with, framed at the image's size): first every line
/// and polygon ring as a stroke of style.line_width, then every point as a dot of
/// style.point_radius, then the labels. Strokes and dots are anti-aliased: a pixel is covered by
/// clamp(half width + 0.5 - d, 0, 1), d the distance from its centre to the path (to the point),
/// each path blended once (its own overlaps do not darken it); alpha, if any, is raised by the
/// coverage. A feature whose properties hold the string `style.label_property` is labelled with it
/// (ASCII; others shown as '?'), upright on the screen, not warped: right of its first point, or
/// centred on the middle vertex of its first line or on the centroid of its first polygon's
/// exterior ring; a label whose anchor is outside the image is left out, and labels may overlap
/// each other. Parts outside the image are clipped.
/// Throws InvalidInput naming "draw_overlay" for an image that is not RGB or RGBA, a style value
/// out of range or data with a vector_data_problem.
void draw_overlay(Image& image, const VectorData& data, const OverlayStyle& style = {});

}  // namespace geolens
