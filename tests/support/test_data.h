#pragma once
// Test support: images and warps for the renderer's, the sources' and the codecs' tests.

#include <functional>

#include "geolens/io/image.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens::test {

using ScreenOf = std::function<Eigen::Vector2d(const Eigen::Vector2d&)>;

/// A cols x rows grid of vertices over the source rectangle [0, width] x [0, height] (cols, rows
/// >= 2), cells split along alternating diagonals, triangles counter-clockwise in source space;
/// each vertex lands on the screen at screen_of(source), framed for screen_width x screen_height.
WarpMesh grid_warp(int cols, int rows, double width, double height, const ScreenOf& screen_of,
                   int screen_width, int screen_height);

/// A width x height image with `channels` channels that uses every byte value, differs between
/// channels and has detail at every scale: (7 x + 13 y + 101 c + x y) mod 256.
Image pattern(int width, int height, int channels);

/// The width x height pixels of `image` from (x, y), which must lie inside it.
Image crop(const Image& image, int x, int y, int width, int height);

/// The identity on a side x side frame with a magnifier over it: the source square of side
/// `source_side` at `source_min` drawn onto the screen square of side `screen_side` at
/// `screen_min` (two more triangles, on top). What a lens's uniform focus is, without a solve.
WarpMesh magnified_patch(int side, const Eigen::Vector2d& source_min, double source_side,
                         const Eigen::Vector2d& screen_min, double screen_side);

}  // namespace geolens::test
