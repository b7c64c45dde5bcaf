#pragma once
// Tiles of a TiledSource drawn with cairo: the one place that turns a cairo surface into the
// texels of a tile (private to the library; the SVG source and the vector map use it).

#include <cairo.h>

#include <array>
#include <cstdint>
#include <functional>

#include "geolens/io/image.h"
#include "geolens/source/source.h"

namespace geolens {

/// The texels of `request` (an RGB tile of a source whose level 0 has `scale` texels per frame
/// pixel) drawn by `draw`: a request.width x request.height cairo surface painted `background`,
/// whose context maps frame pixels to the tile's texels (frame point p lands at texel
/// p * scale / 2^level - (request.x, request.y)), so `draw` works in frame pixels and cairo
/// rasterizes at exactly the tile's resolution, anti-aliased. Texel (i, j) of the tile is the
/// surface's pixel (i, j), whose centre is texel centre (x + i, y + j) of the level, as Source
/// documents. Throws InvalidInput naming `function` if the context ends in an error state.
Image cairo_tile(const TileRequest& request, double scale, const std::array<uint8_t, 3>& background,
                 const std::function<void(cairo_t*)>& draw, const char* function);

/// `image` (3 or 4 channels) as a cairo image surface of its size (RGB24 for RGB, premultiplied
/// ARGB32 for RGBA), to draw on; the caller destroys it.
cairo_surface_t* image_to_cairo(const Image& image);
/// Copies `surface` (made by image_to_cairo from an image of the same size and channels) back into
/// `image`.
void cairo_to_image(cairo_surface_t* surface, Image& image);

}  // namespace geolens
