#pragma once
// Private: exact triangle coverage, shared by the renderer (render.cpp) and the heat map
// (heatmap.cpp).
//
// Coverage is decided exactly: vertices are snapped to 1/256 output pixel and the edge functions
// evaluated in 64-bit integers, with a tie rule (a pixel centre exactly on an edge belongs to the
// triangle whose inward edge normal n has n.x > 0, or n.x == 0 and n.y > 0) that gives a pixel on
// an edge shared by two triangles to exactly one of them. So a mesh draws every covered pixel
// once: no cracks, no double hits. Triangles reaching beyond kGuard pixels are clipped to that
// square first (clip_to_guard), which keeps the integer products below 2^62.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace geolens {

constexpr int kSubpixelBits = 8;
constexpr int64_t kSubpixel = int64_t(1) << kSubpixelBits;
constexpr double kGuard = 1 << 21;  ///< output pixels

inline int64_t floor_div(int64_t a, int64_t b) {  // b > 0
  int64_t q = a / b;
  if (a % b < 0) --q;
  return q;
}

/// Tracks, row by row, the pixel range one edge allows: px <= bound (upper), px >= bound
/// (lower), or all / none for a horizontal edge. The bound floor(value / divisor) is stepped
/// exactly with a quotient and a remainder.
struct EdgeWalker {
  enum Kind { kUpper, kLower, kHorizontal } kind;
  int64_t quotient, remainder, divisor, quotient_step, remainder_step;

  /// Edge from (x0, y0) to (x1, y1) of a positively oriented triangle (fixed point), set up at
  /// the centre of row `row`.
  EdgeWalker(int64_t x0, int64_t y0, int64_t x1, int64_t y1, int row) {
    const int64_t dx = x1 - x0, dy = y1 - y0;
    // Inside: E = dx * (Y - y0) - dy * (X - x0) >= 0, or > 0 unless the tie rule picks this edge.
    const int64_t tie = (dy < 0 || (dy == 0 && dx > 0)) ? 0 : -1;
    const int64_t centre_y = int64_t(row) * kSubpixel + kSubpixel / 2;
    // E at pixel px of the row = value - dy * kSubpixel * px.
    const int64_t value = dx * (centre_y - y0) - dy * (kSubpixel / 2 - x0) + tie;
    const int64_t step = dx * kSubpixel;  // change of value per row
    if (dy == 0) {
      kind = kHorizontal;
      quotient = value;
      quotient_step = step;
      remainder = remainder_step = divisor = 0;
      return;
    }
    kind = dy > 0 ? kUpper : kLower;
    divisor = (dy > 0 ? dy : -dy) * kSubpixel;
    quotient = floor_div(value, divisor);
    remainder = value - quotient * divisor;
    quotient_step = floor_div(step, divisor);
    remainder_step = step - quotient_step * divisor;
  }

  /// Narrows [lo, hi] to the pixels this edge allows on the current row.
  void clip(int64_t& lo, int64_t& hi) const {
    switch (kind) {
      case kUpper:
        hi = std::min(hi, quotient);
        break;
      case kLower:
        lo = std::max(lo, -quotient);
        break;
      case kHorizontal:
        if (quotient < 0) hi = lo - 1;
        break;
    }
  }

  void next_row() {
    quotient += quotient_step;
    remainder += remainder_step;
    if (kind != kHorizontal && remainder >= divisor) {
      remainder -= divisor;
      ++quotient;
    }
  }
};

/// The triangle (x[i], y[i]) (output pixels), or the fan of its part within the guard square
/// [-kGuard, kGuard]^2 (Sutherland-Hodgman; edges shared by two triangles are cut at the same
/// points), as up to 6 triangles in xs, ys. Returns how many.
int clip_to_guard(const double (&x)[3], const double (&y)[3], double (&xs)[6][3],
                  double (&ys)[6][3]);

/// Calls span(py, lo, hi) for every row py in [row_begin, row_end) on which the triangle
/// (x[i], y[i]) (output pixels, either orientation, within the guard square) covers the pixel
/// centres lo..hi (inclusive) of the columns [col_begin, col_end), by the exact rule above.
/// Degenerate triangles cover nothing.
template <class Span>
void for_each_span(const double (&x)[3], const double (&y)[3], int row_begin, int row_end,
                   int col_begin, int col_end, Span&& span) {
  int64_t fx[3], fy[3];
  for (int i = 0; i < 3; ++i) {
    fx[i] = std::llround(x[i] * kSubpixel);
    fy[i] = std::llround(y[i] * kSubpixel);
  }
  const int64_t area = (fx[1] - fx[0]) * (fy[2] - fy[0]) - (fy[1] - fy[0]) * (fx[2] - fx[0]);
  if (area == 0) return;
  if (area < 0) {
    std::swap(fx[1], fx[2]);
    std::swap(fy[1], fy[2]);
  }
  // Rows whose pixel centre lies within the vertical extent.
  const int64_t y_min = std::min({fy[0], fy[1], fy[2]}), y_max = std::max({fy[0], fy[1], fy[2]});
  row_begin = int(
      std::max<int64_t>(row_begin, floor_div(y_min - kSubpixel / 2 + kSubpixel - 1, kSubpixel)));
  row_end = int(std::min<int64_t>(row_end, floor_div(y_max - kSubpixel / 2, kSubpixel) + 1));
  if (row_begin >= row_end) return;
  EdgeWalker edges[3] = {EdgeWalker(fx[0], fy[0], fx[1], fy[1], row_begin),
                         EdgeWalker(fx[1], fy[1], fx[2], fy[2], row_begin),
                         EdgeWalker(fx[2], fy[2], fx[0], fy[0], row_begin)};
  for (int py = row_begin; py < row_end; ++py) {
    int64_t lo = col_begin, hi = col_end - 1;
    for (const EdgeWalker& e : edges) e.clip(lo, hi);
    if (lo <= hi) span(py, int(lo), int(hi));
    for (EdgeWalker& e : edges) e.next_row();
  }
}

}  // namespace geolens
