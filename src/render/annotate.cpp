#include "geolens/render/annotate.h"

#include <algorithm>
#include <string>

#include "geolens/core/errors.h"

namespace geolens {

void outline_regions(Image& image, const std::vector<Region>& regions,
                     const Eigen::Vector2d& origin, double scale_x, double scale_y) {
  require(scale_x > 0 && scale_y > 0, "outline_regions", "scales must be > 0");
  const int w = image.width, h = image.height;
  std::vector<char> inside(size_t(w) * size_t(h));
  const uint8_t red[4] = {220, 30, 30, 255};
  for (const Region& region : regions) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        inside[size_t(y) * size_t(w) + size_t(x)] =
            region.depth(origin + Eigen::Vector2d((x + 0.5) / scale_x, (y + 0.5) / scale_y)) > 0;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const char here = inside[size_t(y) * size_t(w) + size_t(x)];
        bool edge = false;
        for (int dy = -1; dy <= 1 && !edge; ++dy)
          for (int dx = -1; dx <= 1 && !edge; ++dx) {
            const int u = x + dx, v = y + dy;
            edge = u >= 0 && v >= 0 && u < w && v < h &&
                   inside[size_t(v) * size_t(w) + size_t(u)] != here;
          }
        if (!edge) continue;
        uint8_t* p = image.at(x, y);
        for (int c = 0; c < image.channels; ++c) p[c] = image.channels < 3 ? 80 : red[c];
      }
    }
  }
}

Image side_by_side(const Image& left, const Image& right, int gap) {
  require(left.channels == right.channels && gap >= 0, "side_by_side",
          "the images need the same channels (got " + std::to_string(left.channels) + " and " +
              std::to_string(right.channels) + ") and gap >= 0");
  Image out(left.width + gap + right.width, std::max(left.height, right.height), right.channels,
            255);
  paste(out, left, 0, 0);
  paste(out, right, left.width + gap, 0);
  return out;
}

Image to_rgb(const Image& image) {
  if (image.channels == 3) return image;
  Image out(image.width, image.height, 3);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const uint8_t* p = image.at(x, y);
      for (int c = 0; c < 3; ++c) out.at(x, y)[c] = image.channels < 3 ? p[0] : p[c];
    }
  return out;
}

void paste(Image& target, const Image& tile, int left, int top) {
  require(target.channels == tile.channels && left >= 0 && top >= 0 &&
              left + tile.width <= target.width && top + tile.height <= target.height,
          "paste", "the tile must have the target's channels and lie inside it");
  for (int y = 0; y < tile.height; ++y)
    std::copy_n(tile.at(0, y), size_t(tile.width) * size_t(tile.channels),
                target.at(left, top + y));
}

}  // namespace geolens
