#include "source/cairo_tile.h"

#include <algorithm>
#include <memory>
#include <string>

#include "geolens/core/errors.h"

namespace geolens {

namespace {

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

}  // namespace

Image cairo_tile(const TileRequest& request, double scale, const std::array<uint8_t, 3>& background,
                 const std::function<void(cairo_t*)>& draw, const char* function) {
  require(request.channels == 3, function,
          "tiles are RGB, asked for " + std::to_string(request.channels) + " channels");
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, request.width, request.height),
                     &cairo_surface_destroy);
  ContextPtr cr(cairo_create(surface.get()), &cairo_destroy);
  cairo_set_source_rgb(cr.get(), background[0] / 255.0, background[1] / 255.0,
                       background[2] / 255.0);
  cairo_paint(cr.get());
  cairo_translate(cr.get(), -request.x, -request.y);
  const double s = scale / double(int64_t(1) << request.level);
  cairo_scale(cr.get(), s, s);
  draw(cr.get());
  const cairo_status_t status = cairo_status(cr.get());
  require(status == CAIRO_STATUS_SUCCESS, function,
          std::string("drawing a tile failed: ") + cairo_status_to_string(status));
  cairo_surface_flush(surface.get());

  Image tile(request.width, request.height, 3);
  const unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  for (int j = 0; j < request.height; ++j) {
    const uint32_t* row = reinterpret_cast<const uint32_t*>(data + size_t(j) * stride);
    for (int i = 0; i < request.width; ++i) {
      uint8_t* out = tile.at(i, j);
      out[0] = uint8_t(row[i] >> 16);
      out[1] = uint8_t(row[i] >> 8);
      out[2] = uint8_t(row[i]);
    }
  }
  return tile;
}

cairo_surface_t* image_to_cairo(const Image& image) {
  require(image.channels == 3 || image.channels == 4, "image_to_cairo",
          "the image must be RGB or RGBA, got " + std::to_string(image.channels) + " channels");
  const bool alpha = image.channels == 4;
  cairo_surface_t* surface = cairo_image_surface_create(
      alpha ? CAIRO_FORMAT_ARGB32 : CAIRO_FORMAT_RGB24, image.width, image.height);
  cairo_surface_flush(surface);
  unsigned char* data = cairo_image_surface_get_data(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  for (int j = 0; j < image.height; ++j) {
    uint32_t* row = reinterpret_cast<uint32_t*>(data + size_t(j) * stride);
    for (int i = 0; i < image.width; ++i) {
      const uint8_t* p = image.at(i, j);
      const uint32_t a = alpha ? p[3] : 255;
      // premultiplied, rounded
      auto pre = [a](uint32_t c) { return (c * a + 127) / 255; };
      row[i] = a << 24 | pre(p[0]) << 16 | pre(p[1]) << 8 | pre(p[2]);
    }
  }
  cairo_surface_mark_dirty(surface);
  return surface;
}

void cairo_to_image(cairo_surface_t* surface, Image& image) {
  cairo_surface_flush(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  const bool alpha = image.channels == 4;
  for (int j = 0; j < image.height; ++j) {
    const uint32_t* row = reinterpret_cast<const uint32_t*>(data + size_t(j) * stride);
    for (int i = 0; i < image.width; ++i) {
      uint8_t* p = image.at(i, j);
      const uint32_t a = alpha ? row[i] >> 24 : 255;
      auto unpre = [a](uint32_t c) { return a == 0 ? 0u : std::min(255u, (c * 255 + a / 2) / a); };
      p[0] = uint8_t(unpre((row[i] >> 16) & 255));
      p[1] = uint8_t(unpre((row[i] >> 8) & 255));
      p[2] = uint8_t(unpre(row[i] & 255));
      if (alpha) p[3] = uint8_t(a);
    }
  }
}

}  // namespace geolens
