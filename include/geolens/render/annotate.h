#pragma once
// Pictures around the lens's output: region outlines, side-by-side panels, RGB tiles.

#include <Eigen/Core>
#include <vector>

#include "geolens/geometry/roi.h"
#include "geolens/io/image.h"

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

}  // namespace geolens
