#include "geolens/source/source.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "geolens/core/errors.h"

namespace geolens {

Source::Source(int width, int height, int channels, const char* function)
    : width_(width), height_(height), channels_(channels), levels_(1) {
  require(
      width >= 1 && height >= 1, function,
      "source must be non-empty, got " + std::to_string(width) + " x " + std::to_string(height));
  require(channels >= 1 && channels <= 4, function,
          "source channels must be in [1, 4], got " + std::to_string(channels));
  while (level_width(levels_ - 1) > 1 || level_height(levels_ - 1) > 1) ++levels_;
}

TexelRegion Source::fetch(int level, int x, int y, int width, int height) const {
  // Checked without building messages first: the renderer fetches thousands of regions a frame.
  if (level < 0 || level >= levels_ || width < 1 || height < 1 ||
      int64_t(width) * height > (int64_t(1) << 30)) {
    const char* fn = "Source::fetch";
    require(level >= 0 && level < levels_, fn,
            "level must be in [0, " + std::to_string(levels_) + "), got " + std::to_string(level));
    require(width >= 1 && height >= 1, fn,
            "region must be at least 1 x 1, got " + std::to_string(width) + " x " +
                std::to_string(height));
    require(false, fn,
            "region must have at most 2^30 texels, got " + std::to_string(width) + " x " +
                std::to_string(height));
  }
  const int level_w = level_width(level), level_h = level_height(level);
  const int64_t x_end = int64_t(x) + width, y_end = int64_t(y) + height;
  if (x >= 0 && y >= 0 && x_end <= level_w && y_end <= level_h)
    return fetch_inside(level, x, y, width, height);
  // Fetch the part of the level the rectangle clamps to, then repeat its edges.
  auto clamp = [](int64_t v, int size) { return int(std::clamp<int64_t>(v, 0, size - 1)); };
  const int x0 = clamp(x, level_w), x1 = clamp(x_end - 1, level_w);
  const int y0 = clamp(y, level_h), y1 = clamp(y_end - 1, level_h);
  const TexelRegion inside = fetch_inside(level, x0, y0, x1 - x0 + 1, y1 - y0 + 1);
  const size_t texel = size_t(channels_), stride = size_t(width) * texel;
  auto copy = std::make_shared<std::vector<uint8_t>>(stride * size_t(height));
  for (int j = 0; j < height; ++j) {
    const uint8_t* from = inside.at(x0, clamp(int64_t(y) + j, level_h));
    uint8_t* to = copy->data() + size_t(j) * stride;
    for (int i = 0; i < width; ++i) {
      const int column = clamp(int64_t(x) + i, level_w);
      std::memcpy(to + size_t(i) * texel, from + size_t(column - x0) * texel, texel);
    }
  }
  TexelRegion region;
  region.data = copy->data();
  region.stride = stride;
  region.x = x;
  region.y = y;
  region.width = width;
  region.height = height;
  region.channels = channels_;
  region.owner = std::move(copy);
  return region;
}

}  // namespace geolens
