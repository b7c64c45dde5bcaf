#include <stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/render/annotate.h"
#include "render/rasterize.h"

namespace geolens {

std::array<uint8_t, 3> heat_colour(double fraction) {
  // Blue, cyan, green, yellow, red at 0, 1/4, 1/2, 3/4, 1; linear in between.
  static constexpr std::array<std::array<double, 3>, 5> kStops = {
      {{40, 60, 220}, {30, 200, 230}, {40, 190, 60}, {240, 220, 40}, {220, 30, 30}}};
  if (!(fraction >= 0)) fraction = std::isnan(fraction) ? 1.0 : 0.0;
  fraction = std::min(fraction, 1.0);
  const double position = fraction * (kStops.size() - 1);
  const size_t i = std::min(size_t(position), kStops.size() - 2);
  const double s = position - double(i);
  std::array<uint8_t, 3> colour;
  for (size_t c = 0; c < 3; ++c)
    colour[c] = uint8_t(std::lround((1 - s) * kStops[i][c] + s * kStops[i + 1][c]));
  return colour;
}

namespace {

uint8_t luminance(const Image& image, int x, int y) {
  const uint8_t* p = image.at(x, y);
  if (image.channels < 3) return p[0];
  return uint8_t(std::lround(0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]));
}

// Sanitized copy for stb_easy_font, which indexes a table by character - 32.
std::string printable(const std::string& text) {
  std::string out = text;
  for (char& c : out)
    if (c < 32 || c > 126) c = '?';
  return out;
}

void fill_box(Image& image, int x0, int y0, int x1, int y1, std::array<uint8_t, 3> colour) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, image.width);
  y1 = std::min(y1, image.height);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) std::copy(colour.begin(), colour.end(), image.at(x, y));
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

}  // namespace

Image heatmap(const WarpMesh& mesh, const Eigen::VectorXd& values,
              const Eigen::Matrix<bool, Eigen::Dynamic, 1>& flipped, const Image& background,
              double max_value, double opacity) {
  require(values.size() == mesh.F.rows() && flipped.size() == mesh.F.rows(), "heatmap",
          "need one value and one flip flag per triangle");
  require(std::isfinite(max_value) && max_value > 0, "heatmap",
          "max value must be finite and > 0, got " + std::to_string(max_value));
  require(opacity >= 0 && opacity <= 1, "heatmap",
          "opacity must be in [0, 1], got " + std::to_string(opacity));
  require(background.width > 0 && background.height > 0 && mesh.screen_width > 0 &&
              mesh.screen_height > 0,
          "heatmap", "background and screen sizes must be positive");
  const int width = background.width, height = background.height;
  // The triangle covering each pixel centre, the later one in F on top: the renderer's exact
  // coverage (render/rasterize.h), so a pixel on a shared edge belongs to one triangle.
  std::vector<int> owner(size_t(width) * size_t(height), -1);
  const double sx = double(width) / mesh.screen_width, sy = double(height) / mesh.screen_height;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    double x[3], y[3];
    for (int k = 0; k < 3; ++k) {
      x[k] = mesh.screen(mesh.F(f, k), 0) * sx;
      y[k] = mesh.screen(mesh.F(f, k), 1) * sy;
    }
    if (!std::isfinite(x[0] + x[1] + x[2] + y[0] + y[1] + y[2])) continue;
    double xs[6][3], ys[6][3];
    const int pieces = clip_to_guard(x, y, xs, ys);
    for (int i = 0; i < pieces; ++i)
      for_each_span(xs[i], ys[i], 0, height, 0, width, [&](int py, int lo, int hi) {
        std::fill_n(owner.begin() + std::ptrdiff_t(py) * width + lo, hi - lo + 1, int(f));
      });
  }
  Image out(width, height, 3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double grey = luminance(background, x, y);
      const int f = owner[size_t(y) * size_t(width) + size_t(x)];
      uint8_t* pixel = out.at(x, y);
      if (f < 0) {
        std::fill(pixel, pixel + 3, uint8_t(grey));
        continue;
      }
      const std::array<uint8_t, 3> colour =
          flipped(f) ? kFlippedColour : heat_colour(values(f) / max_value);
      for (int c = 0; c < 3; ++c)
        pixel[c] = uint8_t(std::lround(opacity * colour[size_t(c)] + (1 - opacity) * grey));
    }
  }
  return out;
}

int text_width(const std::string& text, int scale) {
  std::string copy = printable(text);
  stb_easy_font_spacing(0);
  return stb_easy_font_width(copy.data()) * scale;
}

void draw_text(Image& image, int x, int y, const std::string& text, int scale,
               std::array<uint8_t, 3> colour) {
  require(image.channels >= 3, "draw_text", "image must be RGB or RGBA");
  require(scale >= 1, "draw_text", "scale must be >= 1, got " + std::to_string(scale));
  std::string copy = printable(text);
  stb_easy_font_spacing(0);
  // One quad is 64 bytes (4 vertices of x, y, z floats and 4 colour bytes); no glyph has more
  // than 16 strokes.
  std::vector<char> buffer(copy.size() * 16 * 64 + 64);
  const int quads =
      stb_easy_font_print(0, 0, copy.data(), nullptr, buffer.data(), int(buffer.size()));
  for (int q = 0; q < quads; ++q) {
    float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
    for (int v = 0; v < 4; ++v) {
      float xy[2];
      std::memcpy(xy, buffer.data() + 64 * q + 16 * v, sizeof xy);
      for (int k = 0; k < 2; ++k) {
        lo[k] = std::min(lo[k], xy[k]);
        hi[k] = std::max(hi[k], xy[k]);
      }
    }
    fill_box(image, x + int(std::lround(lo[0] * scale)), y + int(std::lround(lo[1] * scale)),
             x + int(std::lround(hi[0] * scale)), y + int(std::lround(hi[1] * scale)), colour);
  }
}

Image with_legend(const Image& image, double max_value, const std::string& title) {
  require(image.channels == 3, "with_legend", "image must be RGB");
  require(std::isfinite(max_value) && max_value > 0, "with_legend",
          "max value must be finite and > 0, got " + std::to_string(max_value));
  const int scale = image.width >= 480 ? 2 : 1;
  const int margin = 6 * scale, line = 12 * scale, bar_height = 8 * scale;
  const int strip = margin + line + bar_height + 4 + line + margin;
  Image out(image.width, image.height + strip, 3, 255);
  std::copy(image.pixels.begin(), image.pixels.end(), out.pixels.begin());
  const std::array<uint8_t, 3> ink = {20, 20, 20};
  int y = image.height + margin;
  draw_text(out, margin, y, title, scale, ink);
  y += line;
  const std::string flipped_label = "flipped";
  const int swatch = bar_height;
  const int bar_left = margin + text_width("0", scale) / 2;
  const int bar_right = std::max(
      bar_left + 8, image.width - margin - swatch - 6 * scale - text_width(flipped_label, scale) -
                        text_width(number(max_value), scale) / 2 - 4 * scale);
  for (int x = bar_left; x < bar_right; ++x)
    fill_box(out, x, y, x + 1, y + bar_height,
             heat_colour(double(x - bar_left) / std::max(1, bar_right - bar_left - 1)));
  const int swatch_left = bar_right + text_width(number(max_value), scale) / 2 + 4 * scale;
  fill_box(out, swatch_left, y, swatch_left + swatch, y + bar_height, kFlippedColour);
  draw_text(out, swatch_left + swatch + 3 * scale, y, flipped_label, scale, ink);
  const int tick_y = y + bar_height + 4;
  for (double fraction : {0.0, 0.5, 1.0}) {
    const std::string label = number(fraction * max_value);
    const int x = bar_left + int(std::lround(fraction * (bar_right - bar_left)));
    fill_box(out, x, y + bar_height, x + 1, tick_y, ink);
    draw_text(out, x - text_width(label, scale) / 2, tick_y, label, scale, ink);
  }
  return out;
}

}  // namespace geolens
