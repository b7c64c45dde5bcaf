#pragma once
// The labels of a vector map's points, placed on the output after it is rendered through a warp:
// upright, at the screen size of their text, at their point's mapped position, shown where the
// warp's local scale allows their rank, none overlapping another.

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geolens/io/image.h"
#include "geolens/source/map_style.h"
#include "geolens/warp/warp_map.h"

namespace geolens {

/// A point to label.
struct MapLabel {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  ///< frame pixels (the warp's source)
  std::string text;                                    ///< UTF-8, not empty
  double rank = 0;                                     ///< lower shows first (scalerank)
  double offset = 3;    ///< screen pixels between the point and its text
  MapLabelStyle style;  ///< size, colours, and the rank base
  /// Its layer's zoom range: shown only where the local scale is in [min_zoom, max_zoom) too.
  double min_zoom = 0, max_zoom = std::numeric_limits<double>::infinity();
};

/// A point drawn over the output as an upright dot of a fixed screen size (the points of a
/// labelled layer, which the texture would squash where a lens compresses it).
struct MapDot {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  ///< frame pixels
  double radius = 2;                                   ///< screen pixels, > 0
  std::optional<MapColor> fill, stroke;                ///< none: not filled / stroked
  double width = 1;                                    ///< stroke width, screen pixels
  /// Drawn where the warp's local scale (as for labels) is in [min_zoom, max_zoom).
  double min_zoom = 0, max_zoom = std::numeric_limits<double>::infinity();
};

/// Draws the dots of `dots` that map through `map` (WarpMap::forward) and whose local scale is in
/// their zoom range on `image` (RGB or RGBA, the size `map` is framed at), anti-aliased, in the
/// order given; a dot partly outside the image is clipped. Throws InvalidInput naming
/// "draw_dots" for an image of another channel count.
void draw_dots(Image& image, const std::vector<MapDot>& dots, const WarpMap& map);

/// Where a label went on the screen.
struct PlacedLabel {
  size_t index = 0;                                  ///< into the labels placed
  Eigen::Vector2d anchor = Eigen::Vector2d::Zero();  ///< its point on the screen, pixels
  double scale = 1;  ///< the warp's local scale at its point, screen pixels per frame pixel
  /// The box the text and its halo cover, screen pixels: [x0, x1] x [y0, y1], inside the output.
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double text_x = 0, text_y = 0;  ///< where the text starts on its baseline, screen pixels
};

/// The labels that show on a width x height output rendered through `map` (a WarpMap from frame
/// pixels to the output's pixels, framed_warp_map). A label is a candidate where its position maps
/// (WarpMap::forward: not outside the frame nor under a lens's hidden ring) and the local scale
/// there, the square root of the determinant of the warp's Jacobian on the triangle holding it
/// (exact for the piecewise-linear map), is at least 2^(rank - style.base) and in the label's
/// [min_zoom, max_zoom). Candidates are placed
/// greedily, lowest rank first (the input order among equal ranks, so list the more important
/// first), each at the first of right, left, above, below its point (`offset` away, text
/// centred on that side) whose box, text and halo, lies inside the output and overlaps no box
/// placed before; a label with no such place is left out. Text is measured with cairo's
/// "sans-serif" font at style.size pixels. Safe to call from several threads at once.
std::vector<PlacedLabel> place_labels(const std::vector<MapLabel>& labels, const WarpMap& map,
                                      int width, int height);

/// Draws `placed` (from place_labels over `labels`) on `image` (RGB or RGBA, the size they were
/// placed for): each text upright, anti-aliased, in style.color over a halo of style.halo,
/// style.halo_width pixels wide. Throws InvalidInput naming "draw_labels" for an image of
/// another channel count.
void draw_labels(Image& image, const std::vector<MapLabel>& labels,
                 const std::vector<PlacedLabel>& placed);

}  // namespace geolens
