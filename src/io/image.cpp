#include "geolens/io/image.h"

#include <string>

#include "geolens/core/errors.h"

namespace geolens {

Image::Image(int width, int height, int channels, uint8_t fill)
    : width(width), height(height), channels(channels) {
  require(
      width >= 0 && height >= 0, "Image",
      "size must be non-negative, got " + std::to_string(width) + " x " + std::to_string(height));
  require(channels >= 1 && channels <= 4, "Image",
          "channels must be in [1, 4], got " + std::to_string(channels));
  pixels.assign(size_t(width) * size_t(height) * size_t(channels), fill);
}

}  // namespace geolens
