#pragma once
// The outline of a pixel mask as smooth closed polylines: what lets a mask region be meshed like a
// polygon (its boundary followed by the mesh) instead of as a staircase of pixels.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace geolens {

/// The boundary of a binary raster as closed polylines, smooth and within about half a pixel of
/// the pixels' own edges. Node (i, j) of the width x height raster `inside` (row-major, 1 = in)
/// lies at origin + (i, j) pixels (a mask's pixel centres); nodes beyond the raster are out. The
/// raster, 1 in and 0 out, is smoothed with the binomial filter (1 4 6 4 1) / 16 along each axis
/// (standard deviation 1 node), its level 1/2 traced by marching squares between nodes (a cell
/// whose corners alternate is split as its interpolated centre value says) and each loop
/// simplified by Douglas and Peucker's algorithm to `tolerance` pixels. An outer loop runs
/// counter-clockwise as seen on the screen (y down: a negative shoelace sum), a hole's the other
/// way; loops are not closed explicitly and are listed in the row-major order of their first
/// cell. Parts of the
/// raster thinner than about 1.5 nodes vanish in the smoothing and have no loop. Throws
/// InvalidInput naming "mask_contours" for a raster whose size is not width * height, a size
/// below 1 or a tolerance that is not finite and >= 0.
std::vector<std::vector<Eigen::Vector2d>> mask_contours(const std::vector<uint8_t>& inside,
                                                        int width, int height,
                                                        const Eigen::Vector2d& origin,
                                                        double tolerance = 0.25);

}  // namespace geolens
