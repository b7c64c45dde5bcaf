#include "geolens/render/render.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/thread_pool.h"
#include "geolens/core/errors.h"
#include "geolens/render/annotate.h"
#include "render/rasterize.h"
#include "source/with_channels.h"

namespace geolens {

namespace {

// ---------------------------------------------------------------------------------------------
// Rasterization: exact coverage (render/rasterize.h), drawn block by block.

constexpr int kMaxOutputSide = 1 << 20;  ///< output pixels, keeps the viewport inside the guard
constexpr double kMaxCoordinate = 1e12;  ///< output pixels, keeps clipping arithmetic finite
constexpr double kMinArea = 1e-10;       ///< twice the area, squared output pixels
// A triangle is drawn in blocks of at most kBlockRows x kBlockColumns output pixels, fetching
// for each the texels it can reach: this bounds a fetched region (at most about 2 x 2 texels a
// pixel, as the level of detail is chosen) whatever the triangle's size.
constexpr int kBlockRows = 64;
constexpr int kBlockColumns = 256;

/// Affine map from an output pixel index (px, py) to texel coordinates (u, v) of one mip level.
struct TexelMap {
  double u_x, u_y, u_0;
  double v_x, v_y, v_0;
};

/// What a triangle needs for drawing, computed once per render.
struct Triangle {
  double x[3] = {}, y[3] = {};     ///< screen vertices scaled to output pixels
  int row_begin = 0, row_end = 0;  ///< output rows it may touch; empty when culled or degenerate
  int level = 0;                   ///< finer mip level sampled
  int blend = 0;                   ///< weight of level + 1 in 256ths; 0 samples `level` alone
  TexelMap map[2] = {};            ///< for `level` and `level + 1`
};

struct Target {
  uint8_t* pixels;
  int width;
};

/// A fetched region of a mip level as the inner loop reads it, held by value so that the output
/// writes (which may alias any byte) do not force it to be reloaded.
struct LevelView {
  const uint8_t* texels;   ///< the region's first texel
  size_t stride;           ///< bytes per row
  int x_offset, y_offset;  ///< 1 + the level texel indices of the region's first texel
  int x_last, y_last;      ///< the region's last texel, relative to its first
  double u_min, u_max;     ///< texel coordinates are clamped to these
  double v_min, v_max;
};

LevelView level_view(const TexelRegion& region) {
  return {region.data,      region.stride,
          region.x + 1,     region.y + 1,
          region.width - 1, region.height - 1,
          region.x - 1.0,   double(region.x + region.width - 1),
          region.y - 1.0,   double(region.y + region.height - 1)};
}

/// Bilinear sample of a level at texel coordinates (u, v) (texel centres at integers),
/// clamp-to-edge, with 8-bit sub-texel weights as texture hardware uses: writes 65536 times the
/// value to out[0..C). Clamps to the region, which holds every texel the triangle reads (where
/// it meets the level's edge, the region's edge is the level's): so the result is that of the
/// whole level, and reads never leave the region.
template <int C>
[[gnu::always_inline]] inline void bilinear_fixed(const LevelView& level, double u, double v,
                                                  int32_t* out) {
  if (!(u >= level.u_min)) u = level.u_min;  // written so that NaN clamps too
  if (!(u <= level.u_max)) u = level.u_max;
  if (!(v >= level.v_min)) v = level.v_min;
  if (!(v <= level.v_max)) v = level.v_max;
  // Rounded to the nearest 1/256 texel; u >= u_min >= -1, so the truncation rounds.
  const int64_t u_fixed = int64_t((u + 1) * 256 + 0.5), v_fixed = int64_t((v + 1) * 256 + 0.5);
  // Relative to the region's first texel.
  const int x = int(u_fixed >> 8) - level.x_offset, y = int(v_fixed >> 8) - level.y_offset;
  const int32_t fx = int32_t(u_fixed & 255), fy = int32_t(v_fixed & 255);
  const int x0 = std::max(x, 0), x1 = std::min(x + 1, level.x_last);
  const int y0 = std::max(y, 0), y1 = std::min(y + 1, level.y_last);
  const uint8_t* row0 = level.texels + size_t(y0) * level.stride;
  const uint8_t* row1 = level.texels + size_t(y1) * level.stride;
  const uint8_t* a = row0 + x0 * C;
  const uint8_t* b = row0 + x1 * C;
  const uint8_t* c = row1 + x0 * C;
  const uint8_t* d = row1 + x1 * C;
  for (int k = 0; k < C; ++k) {
    const int32_t top = (int32_t(a[k]) << 8) + (int32_t(b[k]) - int32_t(a[k])) * fx;
    const int32_t bottom = (int32_t(c[k]) << 8) + (int32_t(d[k]) - int32_t(c[k])) * fx;
    out[k] = (top << 8) + (bottom - top) * fy;
  }
}

/// Shades pixels [lo, hi] of output row `py`, sampling `fine` (and `coarse` when kBlend).
template <int C, bool kBlend>
void shade_span(const Triangle& t, LevelView fine, LevelView coarse, int py, int lo, int hi,
                uint8_t* row) {
  const TexelMap m0 = t.map[0], m1 = t.map[1];
  const double u0 = m0.u_y * py + m0.u_0, v0 = m0.v_y * py + m0.v_0;
  const double u1 = m1.u_y * py + m1.u_0, v1 = m1.v_y * py + m1.v_0;
  const uint32_t w1 = uint32_t(t.blend), w0 = 256 - w1;
  for (int px = lo; px <= hi; ++px) {
    int32_t a[C];
    bilinear_fixed<C>(fine, u0 + m0.u_x * px, v0 + m0.v_x * px, a);
    if constexpr (kBlend) {
      int32_t b[C];
      bilinear_fixed<C>(coarse, u1 + m1.u_x * px, v1 + m1.v_x * px, b);
      for (int k = 0; k < C; ++k)  // < 2^32: 255 * 2^16 * 256 + 2^23
        row[px * C + k] = uint8_t((uint32_t(a[k]) * w0 + uint32_t(b[k]) * w1 + (1u << 23)) >> 24);
    } else {
      for (int k = 0; k < C; ++k) row[px * C + k] = uint8_t((a[k] + (1 << 15)) >> 16);
    }
  }
}

/// Draws the part of the triangle (x[i], y[i]) (output pixels, within the guard square) in the
/// block of rows [row_begin, row_end) and columns [col_begin, col_end), shading with `t` from
/// `fine` (level t.level) and `coarse` (t.level + 1, read when t.blend > 0).
template <int C>
void fill(const double (&x)[3], const double (&y)[3], const Triangle& t, const LevelView& fine,
          const LevelView& coarse, int row_begin, int row_end, int col_begin, int col_end,
          const Target& target) {
  for_each_span(x, y, row_begin, row_end, col_begin, col_end, [&](int py, int lo, int hi) {
    uint8_t* row = target.pixels + size_t(py) * size_t(target.width) * C;
    if (t.blend > 0)
      shade_span<C, true>(t, fine, coarse, py, lo, hi, row);
    else
      shade_span<C, false>(t, fine, fine, py, lo, hi, row);
  });
}

/// The texels of `level` that shading output pixels [px_lo, px_hi] x [py_lo, py_hi] through
/// `map` may read, clamped to the level: the bounding box of the block's corners mapped to
/// texel coordinates, widened by a texel for the bilinear neighbour and the 1/256 rounding.
TexelRegion fetch_reach(const Source& source, int level, const TexelMap& map, int px_lo, int px_hi,
                        int py_lo, int py_hi) {
  // As shade_span computes them; the map is affine, so the block's image is within the corners'.
  double u[4], v[4];
  for (int i = 0; i < 4; ++i) {
    const int px = i & 1 ? px_hi : px_lo, py = i & 2 ? py_hi : py_lo;
    u[i] = (map.u_y * py + map.u_0) + map.u_x * px;
    v[i] = (map.v_y * py + map.v_0) + map.v_x * px;
  }
  double u_min = std::min(std::min(u[0], u[1]), std::min(u[2], u[3]));
  double u_max = std::max(std::max(u[0], u[1]), std::max(u[2], u[3]));
  double v_min = std::min(std::min(v[0], v[1]), std::min(v[2], v[3]));
  double v_max = std::max(std::max(v[0], v[1]), std::max(v[2], v[3]));
  if (std::isnan(u[0] + u[1] + u[2] + u[3])) u_min = u_max = std::nan("");  // the whole width
  if (std::isnan(v[0] + v[1] + v[2] + v[3])) v_min = v_max = std::nan("");
  // [floor(min) - 1, floor(max) + 2], clamped to [0, size - 1] (NaN: the whole side).
  auto first = [](double a, int size) {
    a = std::floor(a) - 1;
    if (!(a >= 0)) a = 0;
    if (!(a <= size - 1)) a = size - 1;
    return int(a);
  };
  auto last = [](double b, int size, int first) {
    b = std::floor(b) + 2;
    if (!(b <= size - 1)) b = size - 1;
    if (!(b >= first)) b = first;
    return int(b);
  };
  const int w = source.level_width(level), h = source.level_height(level);
  const int x0 = first(u_min, w), x1 = last(u_max, w, x0);
  const int y0 = first(v_min, h), y1 = last(v_max, h, y0);
  return source.fetch(level, x0, y0, x1 - x0 + 1, y1 - y0 + 1);
}

/// False when the block of pixel centres [px_lo, px_hi] x [py_lo, py_hi], widened by a pixel
/// (more than the vertex snapping moves an edge), lies wholly outside an edge of triangle `t`.
bool may_touch(const Triangle& t, int px_lo, int px_hi, int py_lo, int py_hi) {
  const double x0 = px_lo - 0.5, x1 = px_hi + 1.5, y0 = py_lo - 0.5, y1 = py_hi + 1.5;
  const double area = (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.y[1] - t.y[0]) * (t.x[2] - t.x[0]);
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const double ex = t.x[j] - t.x[i], ey = t.y[j] - t.y[i];
    auto outside = [&](double x, double y) {
      return (ex * (y - t.y[i]) - ey * (x - t.x[i])) * area < 0;
    };
    if (outside(x0, y0) && outside(x1, y0) && outside(x0, y1) && outside(x1, y1)) return false;
  }
  return true;
}

/// Draws triangle `t` in rows [row_begin, row_end), clipping it to the guard square when it
/// reaches beyond, block by block: each block it may touch fetches the texels it can reach.
template <int C>
void draw(const Triangle& t, const Source& source, int row_begin, int row_end,
          const Target& target) {
  // The triangle, or the fan of its part within the guard square.
  double xs[6][3], ys[6][3];
  const int count = clip_to_guard(t.x, t.y, xs, ys);
  // Columns whose pixel centres it may cover, with a pixel of slack for the snapping.
  const double x_min = std::min({t.x[0], t.x[1], t.x[2]}),
               x_max = std::max({t.x[0], t.x[1], t.x[2]});
  const int col_begin = int(std::max(0.0, std::floor(x_min - 1)));
  const int col_end = int(std::min(double(target.width), std::ceil(x_max + 1)));
  const bool single_block =
      row_end - row_begin <= kBlockRows && col_end - col_begin <= kBlockColumns;
  for (int r = row_begin; r < row_end; r += kBlockRows) {
    const int r_end = std::min(row_end, r + kBlockRows);
    for (int c = col_begin; c < col_end; c += kBlockColumns) {
      const int c_end = std::min(col_end, c + kBlockColumns);
      if (!single_block && !may_touch(t, c, c_end - 1, r, r_end - 1)) continue;
      const TexelRegion fine = fetch_reach(source, t.level, t.map[0], c, c_end - 1, r, r_end - 1);
      const TexelRegion coarse =
          t.blend > 0 ? fetch_reach(source, t.level + 1, t.map[1], c, c_end - 1, r, r_end - 1)
                      : TexelRegion();
      const LevelView fine_view = level_view(fine);
      const LevelView coarse_view = t.blend > 0 ? level_view(coarse) : fine_view;
      for (int i = 0; i < count; ++i)
        fill<C>(xs[i], ys[i], t, fine_view, coarse_view, r, r_end, c, c_end, target);
    }
  }
}

/// The map from output pixel indices to texel coordinates of `level`, given the affine map
/// source = origin + J * (screen - screen_origin) in output pixels.
TexelMap texel_map(const double (&J)[2][2], double source_x, double source_y, double screen_x,
                   double screen_y, int level) {
  const double s = std::ldexp(1.0, -level);
  // Pixel (px, py) has its centre at (px + 0.5, py + 0.5); texel centres are at integers.
  const double cx = 0.5 - screen_x, cy = 0.5 - screen_y;
  return {s * J[0][0], s * J[0][1], s * (source_x + J[0][0] * cx + J[0][1] * cy) - 0.5,
          s * J[1][0], s * J[1][1], s * (source_y + J[1][0] * cx + J[1][1] * cy) - 0.5};
}

/// Sets up mesh triangle `f` for drawing into a width x height output.
Triangle set_up(const WarpMesh& mesh, int f, double scale_x, double scale_y, double source_scale,
                double band, int width, int height, int levels) {
  Triangle t;
  double sx[3], sy[3];
  for (int i = 0; i < 3; ++i) {
    const int v = mesh.F(f, i);
    t.x[i] = mesh.screen(v, 0) * scale_x;
    t.y[i] = mesh.screen(v, 1) * scale_y;
    sx[i] = mesh.source(v, 0) * source_scale;
    sy[i] = mesh.source(v, 1) * source_scale;
  }
  const double x_min = std::min({t.x[0], t.x[1], t.x[2]}),
               x_max = std::max({t.x[0], t.x[1], t.x[2]});
  const double y_min = std::min({t.y[0], t.y[1], t.y[2]}),
               y_max = std::max({t.y[0], t.y[1], t.y[2]});
  // Conservative (one pixel of slack for the snapping); `fill` finds the exact rows.
  if (x_max < -1 || x_min > width + 1 || y_max < -1 || y_min > height + 1) return t;
  const double e1x = t.x[1] - t.x[0], e1y = t.y[1] - t.y[0];
  const double e2x = t.x[2] - t.x[0], e2y = t.y[2] - t.y[0];
  const double det = e1x * e2y - e1y * e2x;
  if (!(std::abs(det) > kMinArea)) return t;
  // J = [source edges] * [screen edges]^-1: source pixels per output pixel.
  const double s1x = sx[1] - sx[0], s1y = sy[1] - sy[0];
  const double s2x = sx[2] - sx[0], s2y = sy[2] - sy[0];
  const double J[2][2] = {{(s1x * e2y - s2x * e1y) / det, (s2x * e1x - s1x * e2x) / det},
                          {(s1y * e2y - s2y * e1y) / det, (s2y * e1x - s1y * e2x) / det}};
  // Largest singular value of J, in closed form.
  const double sigma = 0.5 * (std::hypot(J[0][0] + J[1][1], J[1][0] - J[0][1]) +
                              std::hypot(J[0][0] - J[1][1], J[1][0] + J[0][1]));
  const double lod = sigma > 1 ? std::min(std::log2(sigma), double(levels - 1)) : 0.0;  // NaN: 0
  t.level = int(lod);
  // The weight of the coarser level: across the band about the midway point between the two.
  const double blend = std::clamp((lod - t.level - 0.5) / band + 0.5, 0.0, 1.0);
  t.blend = int(std::lround(blend * 256));  // the blend has 8 bits, like the weights
  if (t.blend == 256) {
    t.blend = 0;
    ++t.level;
  }
  t.map[0] = texel_map(J, sx[0], sy[0], t.x[0], t.y[0], t.level);
  if (t.blend > 0) t.map[1] = texel_map(J, sx[0], sy[0], t.x[0], t.y[0], t.level + 1);
  t.row_begin = int(std::max(0.0, std::floor(y_min - 1)));
  t.row_end = int(std::min(double(height), std::ceil(y_max + 1)));
  return t;
}

void validate(const WarpMesh& mesh, const RenderOptions& options) {
  const char* fn = "render";
  require(options.width >= 1 && options.width <= kMaxOutputSide, fn,
          "width must be in [1, " + std::to_string(kMaxOutputSide) + "], got " +
              std::to_string(options.width));
  require(options.height >= 1 && options.height <= kMaxOutputSide, fn,
          "height must be in [1, " + std::to_string(kMaxOutputSide) + "], got " +
              std::to_string(options.height));
  require(options.threads >= 0 && options.threads <= ThreadPool::kMaxThreads, fn,
          "threads must be in [0, " + std::to_string(ThreadPool::kMaxThreads) + "], got " +
              std::to_string(options.threads));
  require(std::isfinite(options.source_scale) && options.source_scale > 0, fn,
          "source_scale must be finite and > 0, got " + number_text(options.source_scale));
  require(options.level_band > 0 && options.level_band <= 1, fn,
          "level_band must be in (0, 1], got " + number_text(options.level_band));
  require(mesh.screen_width > 0 && mesh.screen_height > 0, fn,
          "mesh.screen_width and mesh.screen_height must be > 0, got " +
              std::to_string(mesh.screen_width) + " x " + std::to_string(mesh.screen_height));
  require(mesh.source.rows() == mesh.screen.rows(), fn,
          "mesh.source has " + std::to_string(mesh.source.rows()) + " rows but mesh.screen has " +
              std::to_string(mesh.screen.rows()));
  // Find the first offender, then build one message: messages are not built per element.
  const Eigen::Index vertices = mesh.screen.rows();
  const int* index = mesh.F.data();  // column-major
  const Eigen::Index index_count = mesh.F.size();
  const Eigen::Index bad_index =
      std::find_if(index, index + index_count, [&](int v) { return v < 0 || v >= vertices; }) -
      index;
  require(bad_index == index_count, fn, [&] {
    if (bad_index == index_count) return std::string();
    const Eigen::Index f = bad_index % mesh.F.rows(), i = bad_index / mesh.F.rows();
    return "mesh.F(" + std::to_string(f) + ", " + std::to_string(i) +
           ") = " + std::to_string(mesh.F(f, i)) + " is not a vertex index in [0, " +
           std::to_string(vertices) + ")";
  }());
  Eigen::Index bad_source = 0;
  while (bad_source < vertices && std::isfinite(mesh.source(bad_source, 0)) &&
         std::isfinite(mesh.source(bad_source, 1)))
    ++bad_source;
  require(bad_source == vertices, fn,
          "mesh.source row " + std::to_string(bad_source) + " is not finite");
  const double scale_x = double(options.width) / mesh.screen_width;
  const double scale_y = double(options.height) / mesh.screen_height;
  Eigen::Index bad_screen = 0;
  while (bad_screen < vertices &&
         std::abs(mesh.screen(bad_screen, 0) * scale_x) <= kMaxCoordinate &&
         std::abs(mesh.screen(bad_screen, 1) * scale_y) <= kMaxCoordinate)
    ++bad_screen;
  require(bad_screen == vertices, fn, [&] {
    if (bad_screen == vertices) return std::string();
    return "mesh.screen row " + std::to_string(bad_screen) + " = (" +
           std::to_string(mesh.screen(bad_screen, 0)) + ", " +
           std::to_string(mesh.screen(bad_screen, 1)) +
           ") is not finite or beyond 1e12 output pixels";
  }());
}

}  // namespace

Image render(const WarpMesh& mesh, const Source& source, const RenderOptions& options) {
  validate(mesh, options);
  const int width = options.width, height = options.height, C = source.channels();
  // The caller's pool, or one of options.threads for this call.
  std::unique_ptr<ThreadPool> own_pool;
  if (options.pool == nullptr) own_pool = std::make_unique<ThreadPool>(options.threads);
  ThreadPool& pool = options.pool != nullptr ? *options.pool : *own_pool;
  const int threads = pool.size();
  const double scale_x = double(width) / mesh.screen_width;
  const double scale_y = double(height) / mesh.screen_height;

  const int triangle_count = int(mesh.F.rows());
  std::vector<Triangle> triangles(static_cast<size_t>(triangle_count));
  constexpr int kChunk = 1024;
  pool.run(size_t((triangle_count + kChunk - 1) / kChunk), [&](size_t i) {
    const int chunk = int(i);
    const int end = std::min(triangle_count, (chunk + 1) * kChunk);
    for (int f = chunk * kChunk; f < end; ++f)
      triangles[size_t(f)] = set_up(mesh, f, scale_x, scale_y, options.source_scale,
                                    options.level_band, width, height, source.levels());
  });

  Image out(width, height, C);
  const Target target{out.pixels.data(), width};
  // Horizontal bands, a few per thread for balance; each draws every triangle clipped to its
  // rows, in mesh order, so the result does not depend on the thread count.
  const int bands = threads == 1 ? 1 : std::min(height, 4 * threads);
  pool.run(size_t(bands), [&](size_t index) {
    const int band = int(index);
    const int row_begin = int(int64_t(height) * band / bands);
    const int row_end = int(int64_t(height) * (band + 1) / bands);
    with_channels(C, [&](auto channels) {
      constexpr int kC = decltype(channels)::value;
      uint8_t* band_pixels = out.at(0, row_begin);
      const size_t band_size = size_t(row_end - row_begin) * size_t(width) * kC;
      for (size_t i = 0; i < band_size; i += kC)
        for (int k = 0; k < kC; ++k) band_pixels[i + k] = options.background[size_t(k)];
      for (const Triangle& t : triangles)
        if (t.row_begin < row_end && t.row_end > row_begin)
          draw<kC>(t, source, std::max(row_begin, t.row_begin), std::min(row_end, t.row_end),
                   target);
    });
  });
  return out;
}

Image render(const WarpMesh& warp, const SourceFile& file, RenderOptions options) {
  options.source_scale = file.scale;
  options.level_band = file.level_band;
  Image image = render(warp, *file.source, options);
  if (!file.overlay) return image;
  if (image.channels < 3) image = to_rgb(image);
  file.overlay(image, framed_warp_map(warp, options.width, options.height));
  return image;
}

}  // namespace geolens
