#include "geometry/mask_contour.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <unordered_map>

#include "geolens/core/errors.h"
#include "geometry/polygon.h"

namespace geolens {
namespace {

// Nodes added around the raster: the filter's reach (2) and one more, so every loop closes.
constexpr int kPad = 3;

/// The raster padded by kPad outside nodes and smoothed by (1 4 6 4 1) / 16 along each axis.
std::vector<double> smoothed(const std::vector<uint8_t>& inside, int width, int height, int w,
                             int h) {
  static constexpr std::array<double, 5> kTaps = {1 / 16.0, 4 / 16.0, 6 / 16.0, 4 / 16.0, 1 / 16.0};
  auto in = [&](int i, int j) {
    i -= kPad;
    j -= kPad;
    return i >= 0 && j >= 0 && i < width && j < height && inside[size_t(j) * width + i] ? 1.0 : 0.0;
  };
  std::vector<double> rows(size_t(w) * h, 0.0), out(size_t(w) * h, 0.0);
  for (int j = 0; j < h; ++j)
    for (int i = 2; i < w - 2; ++i) {
      double s = 0;
      for (int k = -2; k <= 2; ++k) s += kTaps[size_t(k + 2)] * in(i + k, j);
      rows[size_t(j) * w + i] = s;
    }
  for (int j = 2; j < h - 2; ++j)
    for (int i = 0; i < w; ++i) {
      double s = 0;
      for (int k = -2; k <= 2; ++k) s += kTaps[size_t(k + 2)] * rows[size_t(j + k) * w + i];
      out[size_t(j) * w + i] = s;
    }
  return out;
}

/// Where the level 1/2 of `v` (the smoothed raster, w nodes a row) crosses lattice edge `edge`,
/// pixels: the edge's nodes' values interpolated linearly, node (i, j) at origin + (i, j) - kPad.
/// Crossings live on lattice edges: edge 2 (j w + i) runs from node (i, j) to (i + 1, j),
/// edge 2 (j w + i) + 1 from (i, j) to (i, j + 1).
Eigen::Vector2d crossing(const std::vector<double>& v, int w, const Eigen::Vector2d& origin,
                         long edge) {
  auto value = [&](int i, int j) { return v[size_t(j) * w + i]; };
  const int i = int((edge / 2) % w), j = int((edge / 2) / w);
  const int i2 = i + (edge % 2 == 0), j2 = j + (edge % 2 == 1);
  const double a = value(i, j), b = value(i2, j2);
  const double t = (0.5 - a) / (b - a);
  return Eigen::Vector2d(origin.x() - kPad + i + t * (i2 - i),
                         origin.y() - kPad + j + t * (j2 - j));
}

/// The cells' segments of the level 1/2, each from the crossing where the walk (i, j) ->
/// (i + 1, j) -> (i + 1, j + 1) -> (i, j + 1) around its cell enters the inside to the one where
/// it leaves: next[entry] = exit. A crossing is an entry of one of its two cells and an exit of
/// the other, so the segments chain.
struct Segments {
  std::unordered_map<long, long> next;
  std::vector<long> starts;  // in row-major order of their cells
};

/// Adds the segments of cell (i, j) of `v` (w nodes a row) to `segments`.
void add_cell_segments(const std::vector<double>& v, int w, int i, int j, Segments& segments) {
  auto value = [&](int x, int y) { return v[size_t(y) * w + x]; };
  const std::array<int, 4> ci = {i, i + 1, i + 1, i}, cj = {j, j, j + 1, j + 1};
  const std::array<long, 4> side = {2L * (long(j) * w + i), 2L * (long(j) * w + i + 1) + 1,
                                    2L * (long(j + 1) * w + i), 2L * (long(j) * w + i) + 1};
  std::array<bool, 4> in;
  for (int k = 0; k < 4; ++k) in[size_t(k)] = value(ci[size_t(k)], cj[size_t(k)]) >= 0.5;
  std::array<long, 2> enter, leave;
  int entries = 0, exits = 0;
  for (int k = 0; k < 4; ++k) {
    const bool a = in[size_t(k)], b = in[size_t((k + 1) % 4)];
    if (a && !b) leave[size_t(exits++)] = side[size_t(k)];
    if (!a && b) enter[size_t(entries++)] = side[size_t(k)];
  }
  if (entries == 0) return;
  std::unordered_map<long, long>& next = segments.next;
  if (entries == 2) {
    // A saddle: corners in, out, in, out. Inside at the centre, the segments cut off the out
    // corners (each entry joins the exit just before it); outside, the in corners.
    double centre = 0;
    for (int k = 0; k < 4; ++k) centre += value(ci[size_t(k)], cj[size_t(k)]) / 4;
    // The walk from corner 0 meets the crossings in the order: exit or entry first.
    const bool exit_first = in[0];
    const bool cut_out = centre >= 0.5;
    // exit_first: order x0 e0 x1 e1; an out corner lies between x_k and e_k.
    if (exit_first == cut_out) {
      next[enter[0]] = leave[0];
      next[enter[1]] = leave[1];
    } else {
      next[enter[0]] = leave[1];
      next[enter[1]] = leave[0];
    }
    segments.starts.push_back(enter[0]);
    segments.starts.push_back(enter[1]);
  } else {
    next[enter[0]] = leave[0];
    segments.starts.push_back(enter[0]);
  }
}

/// The segments chained into loops, from each start not yet on a loop; a loop of at least 3
/// points is kept, simplified to `tolerance` pixels.
std::vector<std::vector<Eigen::Vector2d>> chain_loops(const Segments& segments,
                                                      const std::vector<double>& v, int w,
                                                      const Eigen::Vector2d& origin,
                                                      double tolerance) {
  std::vector<std::vector<Eigen::Vector2d>> loops;
  std::unordered_map<long, char> used;
  for (const long start : segments.starts) {
    if (used.count(start)) continue;
    std::vector<Eigen::Vector2d> loop;
    long edge = start;
    while (!used.count(edge)) {
      used[edge] = 1;
      loop.push_back(crossing(v, w, origin, edge));
      edge = segments.next.at(edge);
    }
    if (loop.size() >= 3) loops.push_back(simplify_loop(loop, tolerance));
  }
  return loops;
}

}  // namespace

std::vector<std::vector<Eigen::Vector2d>> mask_contours(const std::vector<uint8_t>& inside,
                                                        int width, int height,
                                                        const Eigen::Vector2d& origin,
                                                        double tolerance) {
  const char* fn = "mask_contours";
  require(width >= 1 && height >= 1 && inside.size() == size_t(width) * size_t(height), fn,
          "the raster must have width * height >= 1 nodes, got " + std::to_string(inside.size()) +
              " for " + std::to_string(width) + " x " + std::to_string(height));
  require(std::isfinite(tolerance) && tolerance >= 0, fn,
          "tolerance must be finite and >= 0, got " + std::to_string(tolerance));
  const int w = width + 2 * kPad, h = height + 2 * kPad;
  const std::vector<double> v = smoothed(inside, width, height, w, h);
  // Marching squares: every cell's segments, then chained.
  Segments segments;
  for (int j = 0; j + 1 < h; ++j)
    for (int i = 0; i + 1 < w; ++i) add_cell_segments(v, w, i, j, segments);
  return chain_loops(segments, v, w, origin, tolerance);
}

}  // namespace geolens
