#include "source/convert_channels.h"

#include <utility>

namespace geolens {

Image convert_channels(Image image, int channels) {
  if (image.channels == channels) return image;
  Image out(image.width, image.height, channels, 255);
  const bool from_colour = image.channels >= 3, to_colour = channels >= 3;
  const bool from_alpha = image.channels % 2 == 0, to_alpha = channels % 2 == 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const uint8_t* in = image.at(x, y);
      uint8_t* to = out.at(x, y);
      if (from_colour && !to_colour)
        to[0] = uint8_t((299 * in[0] + 587 * in[1] + 114 * in[2] + 500) / 1000);
      else
        for (int c = 0; c < (to_colour ? 3 : 1); ++c) to[c] = in[from_colour ? c : 0];
      if (to_alpha && from_alpha) to[channels - 1] = in[image.channels - 1];
    }
  return out;
}

}  // namespace geolens
