#include "source/downsample.h"

#include <algorithm>
#include <cstdint>
#include <string>

#include "geolens/core/errors.h"
#include "source/with_channels.h"

namespace geolens {

Image downsample(const Image& fine) {
  const char* fn = "downsample";
  require(fine.width > 0 && fine.height > 0, fn,
          "image must be non-empty, got " + std::to_string(fine.width) + " x " +
              std::to_string(fine.height));
  require(fine.channels >= 1 && fine.channels <= 4, fn,
          "channels must be in [1, 4], got " + std::to_string(fine.channels));
  require(fine.pixels.size() == size_t(fine.width) * size_t(fine.height) * size_t(fine.channels),
          fn,
          "image has " + std::to_string(fine.pixels.size()) +
              " bytes, expected width * height * channels");
  Image coarse((fine.width + 1) / 2, (fine.height + 1) / 2, fine.channels);
  with_channels(fine.channels, [&](auto channels) {
    constexpr int C = decltype(channels)::value;
    const size_t fine_stride = size_t(fine.width) * C;
    for (int y = 0; y < coarse.height; ++y) {
      const uint8_t* row0 = fine.pixels.data() + size_t(2 * y) * fine_stride;
      const uint8_t* row1 =
          fine.pixels.data() + size_t(std::min(2 * y + 1, fine.height - 1)) * fine_stride;
      uint8_t* out = coarse.at(0, y);
      for (int x = 0; x < coarse.width; ++x) {
        const int x0 = 2 * x * C, x1 = std::min(2 * x + 1, fine.width - 1) * C;
        const int bias = 1 + ((x ^ y) & 1);
        for (int k = 0; k < C; ++k)
          out[x * C + k] =
              uint8_t((row0[x0 + k] + row0[x1 + k] + row1[x0 + k] + row1[x1 + k] + bias) >> 2);
      }
    }
  });
  return coarse;
}

}  // namespace geolens
