#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "geolens/core/errors.h"
#include "geolens/source/source.h"
#include "source/downsample.h"
#include "source/with_channels.h"

namespace geolens {

namespace {

/// `source`, once checked to be a valid level 0.
const Image& checked(const Image& source) {
  require(source.width > 0 && source.height > 0, "MipPyramid",
          "source must be non-empty, got " + std::to_string(source.width) + " x " +
              std::to_string(source.height));
  require(source.channels >= 1 && source.channels <= 4, "MipPyramid",
          "source channels must be in [1, 4], got " + std::to_string(source.channels));
  require(source.pixels.size() ==
              size_t(source.width) * size_t(source.height) * size_t(source.channels),
          "MipPyramid",
          "source has " + std::to_string(source.pixels.size()) +
              " bytes, expected width * height * channels");
  return source;
}

/// Adds `weight` times the bilinear sample of `level` at texel coordinates (u, v) (texel
/// centres at integers) to acc[0..C), clamping to the edge.
template <int C>
void add_bilinear(const Image& level, double u, double v, float weight, float* acc) {
  // Clamp so that the integer parts are in [-1, size - 1]; written so that NaN clamps too.
  const double u_max = level.width - 1, v_max = level.height - 1;
  if (!(u >= -1.0)) u = -1.0;
  if (!(u <= u_max)) u = u_max;
  if (!(v >= -1.0)) v = -1.0;
  if (!(v <= v_max)) v = v_max;
  const double u_floor = std::floor(u), v_floor = std::floor(v);
  const int x = int(u_floor), y = int(v_floor);
  const float fx = float(u - u_floor), fy = float(v - v_floor);
  const int x0 = std::max(x, 0), x1 = std::min(x + 1, level.width - 1);
  const int y0 = std::max(y, 0), y1 = std::min(y + 1, level.height - 1);
  const uint8_t* row0 = level.pixels.data() + size_t(y0) * size_t(level.width) * C;
  const uint8_t* row1 = level.pixels.data() + size_t(y1) * size_t(level.width) * C;
  const uint8_t* a = row0 + x0 * C;
  const uint8_t* b = row0 + x1 * C;
  const uint8_t* c = row1 + x0 * C;
  const uint8_t* d = row1 + x1 * C;
  for (int k = 0; k < C; ++k) {
    const float top = float(a[k]) + fx * float(int(b[k]) - int(a[k]));
    const float bottom = float(c[k]) + fx * float(int(d[k]) - int(c[k]));
    acc[k] += weight * (top + fy * (bottom - top));
  }
}

}  // namespace

MipPyramid::MipPyramid(const Image& source)
    : Source(checked(source).width, source.height, source.channels, "MipPyramid") {
  levels_.reserve(size_t(levels()));
  levels_.push_back(source);
  while (levels_.back().width > 1 || levels_.back().height > 1)
    levels_.push_back(downsample(levels_.back()));
}

void MipPyramid::sample(double x, double y, double lod, float* out) const {
  lod = std::clamp(lod, 0.0, double(levels() - 1));  // NaN stays NaN: handled below
  const int fine = lod > 0 ? int(lod) : 0;
  const float blend = lod > 0 ? float(lod - fine) : 0.0f;
  with_channels(channels(), [&](auto channels) {
    constexpr int C = decltype(channels)::value;
    float acc[C] = {};
    auto add = [&](int level, float weight) {
      const double s = std::ldexp(1.0, -level);
      add_bilinear<C>(levels_[size_t(level)], x * s - 0.5, y * s - 0.5, weight, acc);
    };
    add(fine, 1 - blend);
    if (blend > 0) add(fine + 1, blend);
    std::copy(acc, acc + C, out);
  });
}

TexelRegion MipPyramid::fetch_inside(int level, int x, int y, int width, int height) const {
  const Image& image = levels_[size_t(level)];
  TexelRegion region;
  region.data = image.at(x, y);
  region.stride = size_t(image.width) * size_t(image.channels);
  region.x = x;
  region.y = y;
  region.width = width;
  region.height = height;
  region.channels = image.channels;
  return region;
}

}  // namespace geolens
