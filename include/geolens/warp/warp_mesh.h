#pragma once
// The one product of every lens: a piecewise-linear map from the source image to the screen.

#include <Eigen/Core>

namespace geolens {

/// A triangle mesh carrying, per vertex, where it is in the source image and where it lands
/// on the output screen. Coordinates are pixels, origin top-left, y down.
struct WarpMesh {
  Eigen::MatrixX3i
      F;  ///< #F x 3 vertex indices, oriented so that (b - a) x (c - a) > 0 in source coordinates
  Eigen::MatrixX2d source;  ///< #V x 2 position in the source image, pixels
  Eigen::MatrixX2d screen;  ///< #V x 2 position on the output screen, pixels
  int screen_width = 0;     ///< output width the screen coordinates are framed for, pixels
  int screen_height = 0;    ///< output height, pixels
};

/// The identity on a width x height source (two triangles), framed at the source's size: what
/// a picture of the source without any lens is rendered through.
WarpMesh identity_warp(int width, int height);

}  // namespace geolens
