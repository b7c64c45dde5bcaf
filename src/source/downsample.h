#pragma once
// One level of detail from the next finer one: the 2x2 box filter of the mip pyramid.

#include "geolens/io/image.h"

namespace geolens {

/// The next level of `fine`: ceil(width / 2) x ceil(height / 2) texels, same channels, each the
/// mean of a 2x2 block of `fine` (on an odd side the edge texel is repeated). The rounding
/// alternates in a checkerboard of (x + y) parity of the coarse texel, so that coarse levels
/// do not drift brighter; a tile whose origin is at even fine coordinates is therefore
/// downsampled exactly as the same texels of the whole level are. Throws InvalidInput for an
/// empty image, channels outside [1, 4] or a pixel buffer of the wrong size.
Image downsample(const Image& fine);

}  // namespace geolens
