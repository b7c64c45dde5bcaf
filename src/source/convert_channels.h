#pragma once
// Private: an image converted to another channel count (the level list's images and the tile
// folder's tiles, which may be stored grey, RGB, with or without alpha).

#include "geolens/io/image.h"

namespace geolens {

/// `image` with `channels` channels (in [1, 4]): grey is repeated into RGB, RGB becomes grey by
/// the Rec. 601 luma weights (0.299, 0.587, 0.114), rounded; an alpha channel added is 255, one
/// dropped is discarded (not composited). The same image when the counts agree.
Image convert_channels(Image image, int channels);

}  // namespace geolens
