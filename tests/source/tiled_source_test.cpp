// The tiled source: a 32768 x 32768 procedural source rendered through it, its cache budget,
// agreement with the in-memory MipPyramid, threads, errors.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/render/render.h"
#include "geolens/source/source.h"
#include "geolens/warp/warp_mesh.h"
#include "support/test_data.h"

using geolens::Image;
using geolens::InvalidInput;
using geolens::MipPyramid;
using geolens::RenderOptions;
using geolens::TexelRegion;
using geolens::TileCacheStats;
using geolens::TiledSource;
using geolens::TiledSourceOptions;
using geolens::TileRequest;
using geolens::WarpMesh;

namespace {

constexpr int kSide = 32768;

/// The procedural texel (x, y) of `level`: it encodes its coordinates and its level.
void procedural_texel(int level, int x, int y, uint8_t* out) {
  out[0] = uint8_t(x & 255);
  out[1] = uint8_t(y & 255);
  out[2] = uint8_t((level * 37 + (x >> 8) * 11 + (y >> 8) * 5) & 255);
}

/// A provider computing every level's tiles from the formula, counting its calls.
geolens::TileProvider procedural_provider(std::atomic<int>* calls = nullptr) {
  return [calls](const TileRequest& r) {
    if (calls) ++*calls;
    Image tile(r.width, r.height, 3);
    for (int j = 0; j < r.height; ++j)
      for (int i = 0; i < r.width; ++i) procedural_texel(r.level, r.x + i, r.y + j, tile.at(i, j));
    return tile;
  };
}

/// A provider cutting tiles out of `pyramid`'s levels (only level 0 when `level0_only`).
geolens::TileProvider pyramid_provider(const MipPyramid& pyramid, bool level0_only = false) {
  return [&pyramid, level0_only](const TileRequest& r) {
    if (level0_only && r.level != 0) throw std::logic_error("asked for a coarse level");
    const Image& level = pyramid.level(r.level);
    Image tile(r.width, r.height, r.channels);
    for (int j = 0; j < r.height; ++j)
      std::copy(level.at(r.x, r.y + j), level.at(r.x + r.width, r.y + j), tile.at(0, j));
    return tile;
  };
}

RenderOptions options_for(int width, int height, int threads) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.threads = threads;
  return options;
}

/// The identity warp of a width x height window of the source at (x0, y0), framed for a
/// screen of `screen` x `screen` pixels.
WarpMesh window(double x0, double y0, double width, double height, int screen) {
  WarpMesh mesh = geolens::identity_warp(screen, screen);
  mesh.source.col(0) = mesh.source.col(0) * (width / screen) + Eigen::VectorXd::Constant(4, x0);
  mesh.source.col(1) = mesh.source.col(1) * (height / screen) + Eigen::VectorXd::Constant(4, y0);
  return mesh;
}

/// Expects out(px, py) = the procedural texel (x0 + px, y0 + py) of `level`, every pixel.
void expect_procedural(const Image& out, int level, int x0, int y0) {
  ASSERT_EQ(out.channels, 3);
  for (int py = 0; py < out.height; ++py)
    for (int px = 0; px < out.width; ++px) {
      uint8_t expected[3];
      procedural_texel(level, x0 + px, y0 + py, expected);
      const uint8_t* got = out.at(px, py);
      ASSERT_TRUE(std::equal(got, got + 3, expected))
          << "pixel " << px << ", " << py << ": got " << int(got[0]) << " " << int(got[1]) << " "
          << int(got[2]) << ", expected " << int(expected[0]) << " " << int(expected[1]) << " "
          << int(expected[2]);
    }
}

/// Lens-like meshes over a width x height source, framed for a 320 x 240 screen: a radial
/// magnifier (magnified centre, minified ring), a 3x zoom past the screen's edges, an
/// anisotropic minification, a jittered grid, one with a vertex far beyond the screen.
std::vector<WarpMesh> lens_like_meshes(double width, double height) {
  auto frame = [&](const Eigen::Vector2d& s) {
    return Eigen::Vector2d(s.x() / width * 320, s.y() / height * 240);
  };
  std::vector<WarpMesh> meshes;
  meshes.push_back(geolens::test::grid_warp(
      41, 41, width, height,
      [&](const Eigen::Vector2d& s) {
        const Eigen::Vector2d p = frame(s), c(160, 120), d = p - c;
        const double r = d.norm(), radius = 110;
        if (r == 0 || r >= radius) return p;
        return Eigen::Vector2d(c + d * (std::pow(r / radius, 0.4) / (r / radius)));
      },
      320, 240));
  meshes.push_back(geolens::test::grid_warp(
      9, 9, width, height,
      [&](const Eigen::Vector2d& s) {
        return Eigen::Vector2d(3 * frame(s) - Eigen::Vector2d(320, 240));
      },
      320, 240));
  meshes.push_back(geolens::test::grid_warp(
      9, 9, width, height,
      [&](const Eigen::Vector2d& s) {
        const Eigen::Vector2d p = frame(s);
        return Eigen::Vector2d(0.3 * p.x() + 7, 0.15 * p.y() + 20);
      },
      320, 240));
  meshes.push_back(geolens::test::grid_warp(
      17, 13, width, height,
      [&](const Eigen::Vector2d& s) {
        const Eigen::Vector2d p = frame(s);
        return Eigen::Vector2d(p.x() + 4 * std::sin(p.y() * 0.31),
                               p.y() + 4 * std::cos(p.x() * 0.27));
      },
      320, 240));
  WarpMesh far = geolens::test::grid_warp(5, 5, width, height, frame, 320, 240);
  far.screen.row(12) << 4e9, -3e9;
  meshes.push_back(far);
  return meshes;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// A 32768 x 32768 procedural source

TEST(TiledSourceTest, WholeViewOfA32768SourceShowsLevel5TexelsWithinTheBudget) {
  // 1024 x 1024 from 32768 x 32768: 32 source pixels a screen pixel, level 5, whose texel
  // (px, py) is centred on pixel (px, py): every output pixel is one texel of level 5. The
  // budget (5 tiles) is below level 5's 16 tiles, so tiles are evicted and made again.
  TiledSourceOptions options;
  options.cache_bytes = 5 * 256 * 256 * 3;
  std::atomic<int> calls{0};
  const TiledSource source(kSide, kSide, 3, procedural_provider(&calls), options);
  for (int threads : {1, 2}) {
    const Image out = geolens::render(geolens::identity_warp(kSide, kSide), source,
                                      options_for(1024, 1024, threads));
    ASSERT_EQ(out.width, 1024);
    expect_procedural(out, 5, 0, 0);
  }
  const TileCacheStats stats = source.cache_stats();
  EXPECT_LE(stats.bytes, options.cache_bytes);
  EXPECT_LE(stats.peak_bytes, options.cache_bytes);
  EXPECT_GT(stats.peak_bytes, 4 * 256 * 256 * 3);  // the budget was used
  EXPECT_EQ(stats.tiles_made, size_t(calls.load()));
  EXPECT_GE(calls.load(), 2 * 16);  // evicted between the two renders
}

TEST(TiledSourceTest, ZoomedWindowsShowTheTexelsOfTheirLevel) {
  TiledSourceOptions options;
  options.cache_bytes = 8 << 20;
  std::atomic<int> calls{0};
  const TiledSource source(kSide, kSide, 3, procedural_provider(&calls), options);
  // 1:1 at level 0, near the far corner and across tile borders: the 5 x 5 tiles under it.
  const Image level0 =
      geolens::render(window(30000, 29001, 1024, 1024, 1024), source, options_for(1024, 1024, 2));
  expect_procedural(level0, 0, 30000, 29001);
  EXPECT_LE(calls.load(), 36);  // a window touches the tiles under it, not the level's 16384
  // The same view again comes from the cache.
  const int before = calls.load();
  geolens::render(window(30000, 29001, 1024, 1024, 1024), source, options_for(1024, 1024, 2));
  EXPECT_EQ(calls.load(), before);
  // 2048 x 2048 source pixels on 1024: level 1, texel (15000 + px, 7000 + py).
  const Image level1 =
      geolens::render(window(30000, 14000, 2048, 2048, 1024), source, options_for(1024, 1024, 2));
  expect_procedural(level1, 1, 15000, 7000);
  // The bottom-right corner at level 3, past which the source clamps to its edge.
  const Image corner =
      geolens::render(window(kSide - 8 * 256, kSide - 8 * 256, 8 * 512, 8 * 512, 512), source,
                      options_for(512, 512, 2));
  for (int py = 0; py < 512; ++py)
    for (int px = 0; px < 512; ++px) {
      uint8_t expected[3];
      procedural_texel(3, std::min(kSide / 8 - 256 + px, kSide / 8 - 1),
                       std::min(kSide / 8 - 256 + py, kSide / 8 - 1), expected);
      ASSERT_TRUE(std::equal(corner.at(px, py), corner.at(px, py) + 3, expected))
          << px << ", " << py;
    }
  EXPECT_LE(source.cache_stats().peak_bytes, options.cache_bytes);
}

TEST(TiledSourceTest, MagnifiedWindowIsTheFixedPointBilinearOfTheTexels) {
  // 400 x 400 source pixels at (20400, 13300) on 1000 x 1000: 2.5x, level 0. Pixel px samples
  // texel coordinate u = x0 - 0.3 + 0.4 px, rounded to 1/256 texel (256 (u + 1) has a
  // fractional part that is a multiple of 0.2, never a tie), and blends the 2 x 2 texels with
  // 8-bit weights as the renderer documents. Every pixel is checked, so a fetched region short
  // of a texel at a screen block's edge would show.
  const int x0 = 20400, y0 = 13300;
  TiledSourceOptions options;
  options.cache_bytes = 2 << 20;
  const TiledSource source(kSide, kSide, 3, procedural_provider(), options);
  const Image out =
      geolens::render(window(x0, y0, 400, 400, 1000), source, options_for(1000, 1000, 2));
  // round(256 (t - 0.3 + 0.4 p + 1)) for texel origin t, as an integer: 256 (t + 0.7 + 0.4 p)
  // = (1280 t + 896 + 512 p) / 5.
  auto fixed = [](int t, int p) {
    return (2 * (1280 * int64_t(t) + 896 + 512 * int64_t(p)) + 5) / 10;
  };
  for (int py = 0; py < 1000; ++py)
    for (int px = 0; px < 1000; ++px) {
      const int64_t u = fixed(x0, px), v = fixed(y0, py);
      const int x = int(u >> 8) - 1, y = int(v >> 8) - 1, fx = int(u & 255), fy = int(v & 255);
      uint8_t a[3], b[3], c[3], d[3];
      procedural_texel(0, x, y, a);
      procedural_texel(0, x + 1, y, b);
      procedural_texel(0, x, y + 1, c);
      procedural_texel(0, x + 1, y + 1, d);
      for (int k = 0; k < 3; ++k) {
        const int top = (a[k] << 8) + (b[k] - a[k]) * fx;
        const int bottom = (c[k] << 8) + (d[k] - c[k]) * fx;
        const int expected = ((top << 8) + (bottom - top) * fy + (1 << 15)) >> 16;
        ASSERT_EQ(out.at(px, py)[k], expected) << px << ", " << py << " channel " << k;
      }
    }
  EXPECT_LE(source.cache_stats().peak_bytes, options.cache_bytes);
}

// ---------------------------------------------------------------------------------------------
// Agreement with the in-memory pyramid

TEST(TiledSourceTest, RendersExactlyAsTheMipPyramidOfTheSameImage) {
  for (int channels : {1, 3}) {
    Image image(301, 187, channels);
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        for (int c = 0; c < channels; ++c)
          image.at(x, y)[c] = uint8_t((x * 7 + y * 13 + c * 101 + x * y) % 256);
    const MipPyramid pyramid(image);
    for (bool downsampled : {false, true}) {
      TiledSourceOptions options;
      options.tile_size = 32;
      options.cache_bytes = 6 * 32 * 32 * size_t(channels);  // far less than the image
      options.downsample_levels = downsampled;
      const TiledSource tiles(image.width, image.height, channels,
                              pyramid_provider(pyramid, downsampled), options);
      for (const WarpMesh& mesh : lens_like_meshes(image.width, image.height))
        for (auto [width, height] : {std::pair{320, 240}, std::pair{97, 301}}) {
          // One thread for the pyramid, two for the tiles: neither may change a pixel.
          const Image expected = geolens::render(mesh, pyramid, options_for(width, height, 1));
          const Image got = geolens::render(mesh, tiles, options_for(width, height, 2));
          ASSERT_EQ(got.pixels, expected.pixels)
              << channels << " channels, downsampled " << downsampled << ", " << width << " x "
              << height << ", mesh of " << mesh.F.rows() << " triangles";
        }
      EXPECT_LE(tiles.cache_stats().peak_bytes, options.cache_bytes);
    }
  }
}

TEST(TiledSourceTest, DownsampledLevelsAreTheMipPyramidsLevels) {
  Image image(131, 77, 2);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = uint8_t(i * 13 + i / 7);
  const MipPyramid pyramid(image);
  TiledSourceOptions options;
  options.tile_size = 16;
  options.downsample_levels = true;
  const TiledSource tiles(131, 77, 2, pyramid_provider(pyramid, true), options);
  for (int level = 0; level < pyramid.levels(); ++level) {
    const Image& expected = pyramid.level(level);
    const TexelRegion region = tiles.fetch(level, 0, 0, expected.width, expected.height);
    for (int y = 0; y < expected.height; ++y)
      ASSERT_TRUE(
          std::equal(region.at(0, y), region.at(0, y) + expected.width * 2, expected.at(0, y)))
          << "level " << level << " row " << y;
  }
}

// ---------------------------------------------------------------------------------------------
// Threads

TEST(TiledSourceTest, ConcurrentFetchesAgreeWithThePyramidAndKeepTheBudget) {
  Image image(517, 389, 3);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = uint8_t(i * 29 + i / 11);
  const MipPyramid pyramid(image);
  std::atomic<int> calls{0};
  TiledSourceOptions options;
  options.tile_size = 16;
  options.cache_bytes = 10 * 16 * 16 * 3;
  const geolens::TileProvider cut = pyramid_provider(pyramid);
  const TiledSource tiles(
      517, 389, 3,
      [&](const TileRequest& r) {
        ++calls;
        return cut(r);
      },
      options);
  std::atomic<int> mismatches{0};
  std::vector<std::thread> workers;
  for (int t = 0; t < 4; ++t)
    workers.emplace_back([&, t] {
      unsigned state = 12345u + unsigned(t);
      auto next = [&](int n) {
        state = state * 1664525u + 1013904223u;
        return int((state >> 8) % unsigned(n));
      };
      for (int k = 0; k < 400; ++k) {
        const int level = next(3);
        const Image& l = pyramid.level(level);
        const int x = next(l.width + 20) - 10, y = next(l.height + 20) - 10;
        const int w = 1 + next(40), h = 1 + next(40);
        const TexelRegion region = tiles.fetch(level, x, y, w, h);
        for (int j = 0; j < h; ++j)
          for (int i = 0; i < w; ++i) {
            const uint8_t* expected =
                l.at(std::clamp(x + i, 0, l.width - 1), std::clamp(y + j, 0, l.height - 1));
            if (!std::equal(expected, expected + 3, region.at(x + i, y + j))) ++mismatches;
          }
      }
    });
  for (std::thread& worker : workers) worker.join();
  EXPECT_EQ(mismatches.load(), 0);
  const TileCacheStats stats = tiles.cache_stats();
  EXPECT_LE(stats.peak_bytes, options.cache_bytes);
  EXPECT_EQ(stats.tiles_made, size_t(calls.load()));
}

// ---------------------------------------------------------------------------------------------
// Errors

TEST(TiledSourceTest, RejectsInvalidArguments) {
  const geolens::TileProvider provider = procedural_provider();
  EXPECT_THROW(TiledSource(0, 10, 3, provider), InvalidInput);
  EXPECT_THROW(TiledSource(10, -1, 3, provider), InvalidInput);
  EXPECT_THROW(TiledSource(10, 10, 5, provider), InvalidInput);
  EXPECT_THROW(TiledSource(10, 10, 3, geolens::TileProvider()), InvalidInput);
  for (int tile_size : {0, 7, -2, 32768}) {
    TiledSourceOptions options;
    options.tile_size = tile_size;
    EXPECT_THROW(TiledSource(10, 10, 3, provider, options), InvalidInput) << tile_size;
  }
  TiledSourceOptions small;
  small.tile_size = 64;
  small.cache_bytes = 64 * 64 * 3 - 1;
  try {
    TiledSource(10, 10, 3, provider, small);
    ADD_FAILURE() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("TiledSource"), std::string::npos) << e.what();
  }
}

TEST(TiledSourceTest, AWrongTileOrAFailingProviderReachesTheCaller) {
  TiledSourceOptions options;
  options.tile_size = 16;
  const TiledSource wrong(
      40, 40, 3, [](const TileRequest& r) { return Image(r.width, r.height, 4); }, options);
  try {
    wrong.fetch(0, 20, 20, 3, 3);
    ADD_FAILURE() << "no exception";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("TiledSource"), std::string::npos) << what;
    EXPECT_NE(what.find("tile (1, 1) of level 0"), std::string::npos) << what;
  }
  EXPECT_THROW(geolens::render(geolens::identity_warp(40, 40), wrong, options_for(20, 20, 2)),
               InvalidInput);
  int calls = 0;
  const TiledSource failing(
      40, 40, 1,
      [&](const TileRequest& r) -> Image {
        if (++calls == 1) throw geolens::IoError("provider: disk gone");
        return Image(r.width, r.height, 1, 9);
      },
      options);
  EXPECT_THROW(failing.fetch(0, 0, 0, 2, 2), geolens::IoError);
  // Nothing was cached for the failed tile: the next fetch asks again, and succeeds.
  EXPECT_EQ(failing.fetch(0, 0, 0, 2, 2).at(1, 1)[0], 9);
  EXPECT_EQ(calls, 2);
}
