#pragma once
// Pictures around the lens's output: region outlines, side-by-side panels, RGB tiles.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geolens/geometry/roi.h"
#include "geolens/io/image.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens {

/// Draws the boundary of every region, about 3 pixels wide, in red (grey on 1- and 2-channel
/// images): the pixels with a pixel on the other side of it within 1 pixel. Pixel (x, y) of
/// `image` shows source point origin + ((x + 0.5) / scale_x, (y + 0.5) / scale_y).
void outline_regions(Image& image, const std::vector<Region>& regions,
                     const Eigen::Vector2d& origin, double scale_x, double scale_y);

/// `left` and `right` side by side, `gap` white pixels apart, top-aligned, with `right`'s
/// channels (`left` must have as many).
Image side_by_side(const Image& left, const Image& right, int gap = 8);

/// The image as 3-channel RGB (grey repeated, alpha dropped).
Image to_rgb(const Image& image);

/// Copies `tile` into `target` with its top-left corner at (left, top); both must have the
/// same channels and the tile must lie inside.
void paste(Image& target, const Image& tile, int left, int top);

// Heatmaps of per-triangle values over a rendered warp, with a colour scale and text labels.

/// The colour of `fraction` (clamped to [0, 1]) on a scale from blue (0) through cyan, green and
/// yellow to red (1), as the paper's Fig. 7 colours distortion from zero to its maximum.
std::array<uint8_t, 3> heat_colour(double fraction);

/// Flipped triangles are drawn in this colour, outside the scale.
constexpr std::array<uint8_t, 3> kFlippedColour = {0, 0, 0};

/// Draws every triangle of `mesh` flat on screen in the colour of values(f) / max_value, over
/// the luminance of `background`: pixel = opacity * colour + (1 - opacity) * grey. Flipped
/// triangles (flipped(f)) are kFlippedColour; a pixel whose centre no triangle covers keeps the
/// grey. Screen coordinates are scaled from mesh.screen_width x mesh.screen_height to the
/// background's size; where triangles overlap the later one in F is on top, as in render().
/// @param values   #F values >= 0 (NaN and +inf are drawn red)
/// @param flipped  #F
/// @param background  any channel count; the result is RGB of its size
/// Throws InvalidInput for mismatched sizes, max_value <= 0 or opacity outside [0, 1].
Image heatmap(const WarpMesh& mesh, const Eigen::VectorXd& values,
              const Eigen::Matrix<bool, Eigen::Dynamic, 1>& flipped, const Image& background,
              double max_value, double opacity = 0.75);

/// `image` (RGB) with a legend strip added below it: `title`, the colour scale from 0 to
/// max_value with labelled ticks at 0, max / 2 and max, and the flipped swatch.
Image with_legend(const Image& image, double max_value, const std::string& title);

/// Width of `text` in pixels when drawn at `scale` pixels per font unit (stb_easy_font: capitals
/// are 7 units tall, a line is 12 units).
int text_width(const std::string& text, int scale);

/// Draws `text` (ASCII, one line) with stb_easy_font's stroke font, its top-left corner at (x, y)
/// pixels, `scale` pixels per font unit, clipped to the image. The image must be RGB or RGBA.
void draw_text(Image& image, int x, int y, const std::string& text, int scale,
               std::array<uint8_t, 3> colour);

}  // namespace geolens
