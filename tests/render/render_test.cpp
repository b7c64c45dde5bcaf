#include "geolens/render/render.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>

#include "geolens/core/errors.h"
#include "support/test_data.h"

using geolens::Image;
using geolens::InvalidInput;
using geolens::MipPyramid;
using geolens::RenderOptions;
using geolens::WarpMesh;

namespace {

/// The identity warp of a width x height source, framed for a screen of the same size.
WarpMesh identity_mesh(int width, int height, int cols = 9, int rows = 7) {
  return geolens::test::grid_warp(
      cols, rows, width, height, [](const Eigen::Vector2d& s) { return s; }, width, height);
}

/// A one-pixel grey checkerboard of 0 and 255.
Image checkerboard(int width, int height) {
  Image image(width, height, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at(x, y)[0] = (x + y) % 2 ? 255 : 0;
  return image;
}

/// Grey value 2x + 3y (exactly linear).
Image ramp(int width, int height) {
  Image image(width, height, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at(x, y)[0] = uint8_t(2 * x + 3 * y);
  return image;
}

RenderOptions options_for(int width, int height, int threads = 0) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.threads = threads;
  return options;
}

double mean_abs_diff(const Image& a, const Image& b) {
  double sum = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) sum += std::abs(int(a.pixels[i]) - int(b.pixels[i]));
  return sum / double(a.pixels.size());
}

int max_abs_diff(const Image& a, const Image& b) {
  int worst = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    worst = std::max(worst, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
  return worst;
}

/// Number of pixels whose first channels equal the background.
int count_background(const Image& image, const RenderOptions& options) {
  int count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      count +=
          std::equal(image.at(x, y), image.at(x, y) + image.channels, options.background.begin());
  return count;
}

/// A deterministic value in [-1, 1] for integer (i, j).
double jitter(int i, int j) {
  const unsigned h = unsigned(i * 73856093) ^ unsigned(j * 19349663);
  return double(h % 2001) / 1000.0 - 1.0;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// MipPyramid

TEST(MipPyramidTest, LevelSizesHalveRoundingUpDownTo1x1) {
  const MipPyramid pyramid(geolens::test::pattern(37, 10, 3));
  ASSERT_EQ(pyramid.levels(), 7);  // 37x10, 19x5, 10x3, 5x2, 3x1, 2x1, 1x1
  EXPECT_EQ(pyramid.level(0).width, 37);
  EXPECT_EQ(pyramid.level(0).height, 10);
  for (int i = 1; i < pyramid.levels(); ++i) {
    EXPECT_EQ(pyramid.level(i).width, (pyramid.level(i - 1).width + 1) / 2);
    EXPECT_EQ(pyramid.level(i).height, (pyramid.level(i - 1).height + 1) / 2);
    EXPECT_EQ(pyramid.level(i).channels, 3);
  }
  EXPECT_EQ(pyramid.level(6).width, 1);
  EXPECT_EQ(pyramid.level(6).height, 1);
  EXPECT_EQ(MipPyramid(Image(1, 1, 2)).levels(), 1);
}

TEST(MipPyramidTest, LevelZeroIsTheSource) {
  const Image source = geolens::test::pattern(20, 11, 4);
  EXPECT_EQ(MipPyramid(source).level(0).pixels, source.pixels);
}

TEST(MipPyramidTest, ConstantImageStaysConstantAtEveryLevelAndLod) {
  Image source(13, 7, 4);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 13; ++x)
      for (int c = 0; c < 4; ++c) source.at(x, y)[c] = uint8_t(10 + 70 * c);
  const MipPyramid pyramid(source);
  for (int i = 0; i < pyramid.levels(); ++i) {
    const Image& level = pyramid.level(i);
    for (int y = 0; y < level.height; ++y)
      for (int x = 0; x < level.width; ++x)
        for (int c = 0; c < 4; ++c) ASSERT_EQ(level.at(x, y)[c], 10 + 70 * c) << "level " << i;
  }
  for (double lod : {0.0, 0.3, 1.0, 2.7, 9.0})
    for (double x : {-3.0, 0.2, 6.5, 12.9, 40.0}) {
      float out[4];
      pyramid.sample(x, 3.3, lod, out);
      for (int c = 0; c < 4; ++c) EXPECT_FLOAT_EQ(out[c], 10 + 70 * c);
    }
}

TEST(MipPyramidTest, BoxFilterAveragesAndRepeatsTheOddEdge) {
  Image source(3, 2, 1);
  const uint8_t values[] = {0, 40, 200, 80, 120, 200};
  std::copy(values, values + 6, source.pixels.begin());
  const MipPyramid pyramid(source);
  ASSERT_EQ(pyramid.level(1).width, 2);
  ASSERT_EQ(pyramid.level(1).height, 1);
  EXPECT_EQ(pyramid.level(1).at(0, 0)[0], 60);   // (0 + 40 + 80 + 120) / 4
  EXPECT_EQ(pyramid.level(1).at(1, 0)[0], 200);  // the edge column repeated
  EXPECT_EQ(pyramid.level(2).at(0, 0)[0], 130);  // (60 + 200 + 60 + 200) / 4
}

TEST(MipPyramidTest, CheckerboardAveragesToMidGreyWithoutDrift) {
  const MipPyramid pyramid(checkerboard(64, 64));
  for (int i = 1; i < pyramid.levels(); ++i) {
    const Image& level = pyramid.level(i);
    double sum = 0;
    for (uint8_t v : level.pixels) {
      EXPECT_GE(v, 127);
      EXPECT_LE(v, 128);
      sum += v;
    }
    // Alternating rounding: no level but the 1x1 one drifts from the exact mean.
    if (level.pixels.size() > 1) {
      EXPECT_DOUBLE_EQ(sum / double(level.pixels.size()), 127.5) << "level " << i;
    }
  }
}

TEST(MipPyramidTest, SampleOfALinearRampIsExactAtLevelZero) {
  const MipPyramid pyramid(ramp(40, 20));
  for (double x = 0.5; x <= 39.5; x += 0.37)
    for (double y = 0.5; y <= 19.5; y += 0.61) {
      float out;
      pyramid.sample(x, y, 0.0, &out);
      EXPECT_NEAR(out, 2 * (x - 0.5) + 3 * (y - 0.5), 1e-3) << x << ", " << y;
    }
}

TEST(MipPyramidTest, SampleClampsToTheEdge) {
  const Image source = geolens::test::pattern(10, 6, 3);
  const MipPyramid pyramid(source);
  float out[3];
  pyramid.sample(-5.0, -7.0, 0.0, out);
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(out[c], source.at(0, 0)[c]);
  pyramid.sample(100.0, 5.9, 0.0, out);
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(out[c], source.at(9, 5)[c]);
  pyramid.sample(3.5, 1e30, 0.0, out);
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(out[c], source.at(3, 5)[c]);
}

TEST(MipPyramidTest, FractionalLodBlendsTheTwoAdjacentLevels) {
  const MipPyramid pyramid(checkerboard(32, 32));
  for (double x : {5.5, 6.5, 10.2}) {
    float fine, coarse, blended;
    pyramid.sample(x, 7.5, 2.0, &fine);
    pyramid.sample(x, 7.5, 3.0, &coarse);
    pyramid.sample(x, 7.5, 2.25, &blended);
    EXPECT_NEAR(blended, 0.75f * fine + 0.25f * coarse, 1e-3);
  }
  // At level 0 a pixel centre is black or white; one level up it is grey.
  float out;
  pyramid.sample(5.5, 7.5, 0.0, &out);
  EXPECT_FLOAT_EQ(out, 0.0f);
  pyramid.sample(5.5, 7.5, 1.0, &out);
  EXPECT_NEAR(out, 127.5, 0.5);
  pyramid.sample(5.5, 7.5, 0.5, &out);
  EXPECT_NEAR(out, 0.5 * 127.5, 0.5);
}

TEST(MipPyramidTest, LodClampsToThePyramid) {
  const Image source = geolens::test::pattern(16, 16, 1);
  const MipPyramid pyramid(source);
  float coarsest, beyond, below, zero;
  pyramid.sample(3.0, 4.0, pyramid.levels() - 1, &coarsest);
  pyramid.sample(3.0, 4.0, 100.0, &beyond);
  EXPECT_FLOAT_EQ(beyond, coarsest);
  EXPECT_FLOAT_EQ(coarsest, pyramid.level(pyramid.levels() - 1).pixels[0]);
  pyramid.sample(3.5, 4.5, -2.0, &below);
  pyramid.sample(3.5, 4.5, 0.0, &zero);
  EXPECT_FLOAT_EQ(below, zero);
  EXPECT_FLOAT_EQ(zero, source.at(3, 4)[0]);
}

TEST(MipPyramidTest, RejectsAnInvalidSource) {
  EXPECT_THROW(MipPyramid{Image()}, InvalidInput);
  Image broken(4, 4, 3);
  broken.pixels.resize(5);
  EXPECT_THROW(MipPyramid{broken}, InvalidInput);
}

// ---------------------------------------------------------------------------------------------
// render

TEST(RenderTest, IdentityMeshReproducesTheImage) {
  for (int channels = 1; channels <= 4; ++channels) {
    const Image source = geolens::test::pattern(64, 48, channels);
    const Image out =
        geolens::render(identity_mesh(64, 48), MipPyramid(source), options_for(64, 48));
    ASSERT_EQ(out.width, 64);
    ASSERT_EQ(out.height, 48);
    ASSERT_EQ(out.channels, channels);
    EXPECT_LT(mean_abs_diff(out, source), 1.0);
    EXPECT_LE(max_abs_diff(out, source), 1);
  }
}

TEST(RenderTest, IrregularMeshHasNoCracks) {
  // Jittered interior vertices (screen == source), some exactly on pixel centres and corners;
  // a black source and a white background: any uncovered pixel shows.
  WarpMesh mesh = identity_mesh(64, 64, 11, 11);
  for (int j = 1; j < 10; ++j)
    for (int i = 1; i < 10; ++i) {
      auto v = mesh.screen.row(j * 11 + i);
      if ((i + j) % 3 == 0)
        v = v.array().round() + 0.5;  // a pixel centre
      else if ((i + j) % 3 == 1)
        v = v.array().round();  // a pixel corner
      else
        v += 2.5 * Eigen::Vector2d(jitter(i, j), jitter(j, i)).transpose();
      mesh.source.row(j * 11 + i) = v;
    }
  const MipPyramid pyramid(Image(64, 64, 1, 0));
  for (auto [width, height] : {std::pair{64, 64}, std::pair{100, 70}, std::pair{33, 47}}) {
    const RenderOptions options = options_for(width, height);
    EXPECT_EQ(count_background(geolens::render(mesh, pyramid, options), options), 0)
        << width << " x " << height;
  }
}

TEST(RenderTest, HalfSizeCheckerboardIsMidGreyWithoutAliasing) {
  const MipPyramid pyramid(checkerboard(256, 256));
  const WarpMesh mesh = identity_mesh(256, 256);
  for (int side : {128, 100, 64, 37}) {
    const Image out = geolens::render(mesh, pyramid, options_for(side, side));
    double sum = 0;
    for (uint8_t v : out.pixels) {
      EXPECT_GE(v, 120) << side;
      EXPECT_LE(v, 135) << side;
      sum += v;
    }
    EXPECT_NEAR(sum / double(out.pixels.size()), 127.5, 1.5) << side;
  }
}

TEST(RenderTest, MinifiedPixelsMatchTrilinearSamplesAtTheJacobianLod) {
  // A uniform (and an anisotropic) minification: each output pixel is the trilinear sample at
  // its source point, at lod = log2 of the larger scale factor, so the fractional lod blends
  // two levels.
  const MipPyramid pyramid(geolens::test::pattern(64, 64, 3));
  const WarpMesh mesh = identity_mesh(64, 64);
  for (auto [width, height] : {std::pair{23, 23}, std::pair{40, 20}, std::pair{64, 37}}) {
    const Image out = geolens::render(mesh, pyramid, options_for(width, height));
    const double sx = 64.0 / width, sy = 64.0 / height;
    const double lod = std::log2(std::max(sx, sy));
    for (int py = 0; py < height; ++py)
      for (int px = 0; px < width; ++px) {
        float expected[3];
        pyramid.sample((px + 0.5) * sx, (py + 0.5) * sy, lod, expected);
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(out.at(px, py)[c], expected[c], 1.5)
              << width << " x " << height << " at " << px << ", " << py;
      }
  }
}

TEST(RenderTest, TwoTimesMagnificationPutsAPixelWhereExpected) {
  // A white 2x2 block at source pixels (10..11, 5..6), magnified 2x about the origin.
  Image source(32, 32, 1, 0);
  for (int y = 5; y <= 6; ++y)
    for (int x = 10; x <= 11; ++x) source.at(x, y)[0] = 255;
  const WarpMesh mesh = geolens::test::grid_warp(
      5, 5, 32, 32, [](const Eigen::Vector2d& s) { return Eigen::Vector2d(2 * s); }, 64, 64);
  const Image out = geolens::render(mesh, MipPyramid(source), options_for(64, 64));
  // Magnifying samples level 0: the block's interior stays fully white, far pixels black.
  for (int y = 11; y <= 12; ++y)
    for (int x = 21; x <= 22; ++x) EXPECT_EQ(out.at(x, y)[0], 255) << x << ", " << y;
  EXPECT_EQ(out.at(10, 5)[0], 0);
  EXPECT_EQ(out.at(30, 20)[0], 0);
  // The block's centre (11, 6) lands at (22, 12).
  double sum = 0, cx = 0, cy = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const double v = out.at(x, y)[0];
      sum += v;
      cx += v * (x + 0.5);
      cy += v * (y + 0.5);
    }
  EXPECT_NEAR(cx / sum, 22.0, 1e-2);
  EXPECT_NEAR(cy / sum, 12.0, 1e-2);
}

TEST(RenderTest, MagnifiedRampIsInterpolatedLinearly) {
  const WarpMesh mesh = geolens::test::grid_warp(
      4, 4, 40, 20, [](const Eigen::Vector2d& s) { return Eigen::Vector2d(2 * s); }, 80, 40);
  const Image out = geolens::render(mesh, MipPyramid(ramp(40, 20)), options_for(80, 40));
  for (int py = 1; py < 39; ++py)
    for (int px = 1; px < 79; ++px) {
      const double sx = (px + 0.5) / 2, sy = (py + 0.5) / 2;  // source point of the pixel centre
      EXPECT_NEAR(out.at(px, py)[0], 2 * (sx - 0.5) + 3 * (sy - 0.5), 0.51) << px << ", " << py;
    }
}

TEST(RenderTest, TranslatedMeshMovesPixels) {
  const Image source = geolens::test::pattern(30, 20, 3);
  const WarpMesh mesh = geolens::test::grid_warp(
      4, 3, 30, 20, [](const Eigen::Vector2d& s) { return Eigen::Vector2d(s.x() + 5, s.y() + 3); },
      40, 30);
  RenderOptions options = options_for(40, 30);
  options.background = {1, 2, 3, 99};
  const Image out = geolens::render(mesh, MipPyramid(source), options);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      const bool covered = x >= 5 && x < 35 && y >= 3 && y < 23;
      for (int c = 0; c < 3; ++c) {
        const int expected = covered ? source.at(x - 5, y - 3)[c] : c + 1;
        ASSERT_EQ(out.at(x, y)[c], expected) << x << ", " << y;
      }
    }
}

TEST(RenderTest, UncoveredPixelsGetTheBackground) {
  // The mesh covers exactly the left half of the screen.
  const WarpMesh mesh = geolens::test::grid_warp(
      3, 3, 16, 16, [](const Eigen::Vector2d& s) { return Eigen::Vector2d(s.x() / 2, s.y()); }, 16,
      16);
  RenderOptions options = options_for(16, 16);
  options.background = {7, 8, 9, 10};
  const Image out = geolens::render(mesh, MipPyramid(Image(16, 16, 2, 200)), options);
  ASSERT_EQ(out.channels, 2);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      EXPECT_EQ(out.at(x, y)[0], x < 8 ? 200 : 7) << x << ", " << y;
      EXPECT_EQ(out.at(x, y)[1], x < 8 ? 200 : 8) << x << ", " << y;
    }
  WarpMesh empty = mesh;
  empty.F.resize(0, 3);
  EXPECT_EQ(count_background(geolens::render(empty, MipPyramid(Image(4, 4, 2)), options), options),
            16 * 16);
}

TEST(RenderTest, EitherOrientationRenders) {
  const Image source = geolens::test::pattern(32, 24, 3);
  const MipPyramid pyramid(source);
  WarpMesh mesh = identity_mesh(32, 24);
  const Image reference = geolens::render(mesh, pyramid, options_for(32, 24));
  // Reversed winding: the same triangles.
  WarpMesh reversed = mesh;
  reversed.F.col(1).swap(reversed.F.col(2));
  EXPECT_EQ(geolens::render(reversed, pyramid, options_for(32, 24)).pixels, reference.pixels);
  // A mirrored screen: every triangle is clockwise on screen, and the image is mirrored.
  WarpMesh mirrored = mesh;
  mirrored.screen.col(0) = 32.0 - mesh.screen.col(0).array();
  const Image out = geolens::render(mirrored, pyramid, options_for(32, 24));
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(out.at(x, y)[c], source.at(31 - x, y)[c]);
}

TEST(RenderTest, DegenerateTrianglesAreSkipped) {
  const MipPyramid pyramid(geolens::test::pattern(32, 24, 3));
  const WarpMesh mesh = identity_mesh(32, 24);
  WarpMesh padded = mesh;
  const Eigen::Index n = mesh.F.rows();
  padded.F.conservativeResize(n + 2, 3);
  padded.F.row(n) << 0, 1, 2;       // three collinear vertices of the first grid row
  padded.F.row(n + 1) << 5, 5, 14;  // a repeated vertex
  EXPECT_EQ(geolens::render(padded, pyramid, options_for(32, 24)).pixels,
            geolens::render(mesh, pyramid, options_for(32, 24)).pixels);
}

TEST(RenderTest, TrianglesReachingFarOffScreenAreClipped) {
  // Two huge triangles whose map is the identity cover the whole screen.
  const double far = 1e9;
  WarpMesh mesh;
  mesh.screen.resize(4, 2);
  mesh.screen << -far, -far, far, -far, far, far, -far, far;
  mesh.source = mesh.screen;
  mesh.F.resize(2, 3);
  mesh.F << 0, 1, 2, 0, 2, 3;
  mesh.screen_width = 40;
  mesh.screen_height = 30;
  const Image source = geolens::test::pattern(40, 30, 3);
  const Image out = geolens::render(mesh, MipPyramid(source), options_for(40, 30));
  EXPECT_LE(max_abs_diff(out, source), 1);
}

TEST(RenderTest, ExtremeSourceCoordinatesClampToTheImage) {
  // Finite but absurd source positions: the map overflows, sampling still stays in the image.
  WarpMesh mesh = identity_mesh(16, 16, 3, 3);
  mesh.source(4, 0) = 1e308;
  mesh.source(5, 0) = -1e308;
  mesh.source(7, 1) = 1e308;
  const Image out = geolens::render(mesh, MipPyramid(Image(16, 16, 1, 77)), options_for(16, 16));
  for (uint8_t v : out.pixels) EXPECT_EQ(v, 77);
}

TEST(RenderTest, ResultDoesNotDependOnTheThreadCountAndLaterTrianglesDrawOnTop) {
  // A folded mesh: an extra triangle overlaps the grid and must win wherever it covers.
  WarpMesh mesh = geolens::test::grid_warp(
      12, 12, 64, 64,
      [](const Eigen::Vector2d& s) {
        const Eigen::Vector2d d = s - Eigen::Vector2d(32, 32);
        return Eigen::Vector2d(Eigen::Vector2d(32, 32) + d * (1.5 - d.norm() / 90));
      },
      64, 64);
  const Eigen::Index n = mesh.F.rows();
  mesh.F.conservativeResize(n + 1, 3);
  mesh.F.row(n) << 0, 11, 143;  // the whole source square's diagonal half, drawn last
  const MipPyramid pyramid(geolens::test::pattern(64, 64, 3));
  const Image one = geolens::render(mesh, pyramid, options_for(97, 61, 1));
  for (int threads : {2, 3, 8, 0})
    EXPECT_EQ(geolens::render(mesh, pyramid, options_for(97, 61, threads)).pixels, one.pixels)
        << threads << " threads";
  WarpMesh last_only = mesh;
  last_only.F = mesh.F.bottomRows(1).eval();
  const RenderOptions options = options_for(97, 61, 1);
  const Image top = geolens::render(last_only, pyramid, options);
  int covered = 0;
  for (int y = 0; y < 61; ++y)
    for (int x = 0; x < 97; ++x)
      if (!std::equal(top.at(x, y), top.at(x, y) + 3, options.background.begin())) {
        ++covered;
        for (int c = 0; c < 3; ++c) ASSERT_EQ(one.at(x, y)[c], top.at(x, y)[c]);
      }
  EXPECT_GT(covered, 1000);
}

TEST(RenderTest, SourceScaleSamplesAFinerSourceAsIfTheMeshWereScaled) {
  // A 2x magnification of a 16 x 16 frame drawn from a source 4 times finer (64 x 64): with
  // source_scale 4 the mesh's frame coordinates reach the fine texels, exactly as a mesh with
  // its source coordinates multiplied by 4 does; and the magnified part samples the fine level,
  // not a coarse level upsampled.
  const Image fine = geolens::test::pattern(64, 64, 3);
  const MipPyramid pyramid(fine);
  const auto magnify = [](const Eigen::Vector2d& s) { return Eigen::Vector2d(2 * s); };
  const WarpMesh frame = geolens::test::grid_warp(5, 5, 16, 16, magnify, 32, 32);
  WarpMesh scaled = frame;
  scaled.source *= 4;
  RenderOptions options = options_for(32, 32);
  const Image direct = geolens::render(scaled, pyramid, options);
  options.source_scale = 4;
  const Image through_scale = geolens::render(frame, pyramid, options);
  EXPECT_EQ(max_abs_diff(through_scale, direct), 0);
  // Each output pixel covers 2 x 2 fine texels: level 1 of the pyramid, not level 2 (a frame
  // texel) magnified, which a render without the scale shows.
  const Image level1 = pyramid.level(1);
  EXPECT_LT(mean_abs_diff(through_scale, level1), 1.0);
  options.source_scale = 1;
  const Image coarse = geolens::render(frame, MipPyramid(pyramid.level(2)), options);
  EXPECT_GT(mean_abs_diff(coarse, level1), 4.0);
}

// Level l of this source is the constant 40 l, so a pixel's value tells which levels it blends.
class LevelShade : public geolens::Source {
 public:
  explicit LevelShade(int side) : Source(side, side, 1, "LevelShade") {}

 private:
  geolens::TexelRegion fetch_inside(int level, int x, int y, int width, int height) const override {
    auto texels =
        std::make_shared<std::vector<uint8_t>>(size_t(width) * size_t(height), uint8_t(40 * level));
    return {texels->data(), size_t(width), x, y, width, height, 1, texels};
  }
};

TEST(RenderTest, LevelBandBlendsNeighbouringLevelsOnlyAboutTheirMidpoint) {
  const LevelShade source(256);
  // A 256 px source minified to 256 / 2^lod: every pixel at that level of detail.
  auto shade = [&](double lod, double band) {
    const int side = int(std::lround(256 / std::exp2(lod)));
    const WarpMesh mesh = geolens::test::grid_warp(
        3, 3, 256, 256, [&](const Eigen::Vector2d& s) { return Eigen::Vector2d(s * side / 256); },
        side, side);
    RenderOptions options = options_for(side, side);
    options.level_band = band;
    return double(geolens::render(mesh, source, options).at(side / 2, side / 2)[0]);
  };
  // Trilinear (band 1): level 1 blended with level 2 by the fraction past level 1.
  EXPECT_NEAR(shade(1.3, 1), 40 + 0.3 * 40, 1.0);
  EXPECT_NEAR(shade(1.6, 1), 40 + 0.6 * 40, 1.0);
  // A quarter-level band: one level alone outside 1.375 - 1.625, blended inside it.
  EXPECT_NEAR(shade(1.3, 0.25), 40, 1.0);
  EXPECT_NEAR(shade(1.5, 0.25), 60, 1.0);
  EXPECT_NEAR(shade(1.6, 0.25), 40 + 0.9 * 40, 1.0);
  EXPECT_NEAR(shade(1.7, 0.25), 80, 1.0);
}

TEST(RenderTest, RejectsInvalidInputNamingRender) {
  const MipPyramid pyramid(Image(4, 4, 1));
  const WarpMesh mesh = identity_mesh(4, 4, 3, 3);
  auto expect_invalid = [&](const WarpMesh& m, const RenderOptions& o) {
    try {
      geolens::render(m, pyramid, o);
      ADD_FAILURE() << "expected InvalidInput";
    } catch (const InvalidInput& e) {
      EXPECT_EQ(std::string(e.what()).rfind("render: ", 0), 0u) << e.what();
    }
  };
  expect_invalid(mesh, options_for(0, 4));
  expect_invalid(mesh, options_for(4, -1));
  expect_invalid(mesh, options_for(4, 4, -1));
  for (const double scale : {0.0, -1.0, std::numeric_limits<double>::infinity()}) {
    RenderOptions o = options_for(4, 4);
    o.source_scale = scale;
    expect_invalid(mesh, o);
  }
  for (const double band : {0.0, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
    RenderOptions o = options_for(4, 4);
    o.level_band = band;
    expect_invalid(mesh, o);
  }
  WarpMesh m = mesh;
  m.screen_width = 0;
  expect_invalid(m, options_for(4, 4));
  m = mesh;
  m.source.conservativeResize(m.source.rows() - 1, 2);
  expect_invalid(m, options_for(4, 4));
  m = mesh;
  m.F(3, 1) = int(m.screen.rows());
  expect_invalid(m, options_for(4, 4));
  m = mesh;
  m.F(0, 0) = -1;
  expect_invalid(m, options_for(4, 4));
  m = mesh;
  m.screen(2, 1) = std::numeric_limits<double>::quiet_NaN();
  expect_invalid(m, options_for(4, 4));
  m = mesh;
  m.source(2, 0) = std::numeric_limits<double>::infinity();
  expect_invalid(m, options_for(4, 4));
  m = mesh;
  m.screen(2, 0) = 1e300;
  expect_invalid(m, options_for(4, 4));
}
