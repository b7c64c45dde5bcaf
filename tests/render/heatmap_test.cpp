// Heatmaps: the colour scale's ends, triangles drawn in their value's colour over the background's
// grey, flipped triangles black, the legend strip, and text.

#include <gtest/gtest.h>

#include <cmath>

#include "geolens/core/errors.h"
#include "geolens/render/annotate.h"
#include "geolens/render/render.h"
#include "support/test_data.h"

namespace geolens {
namespace {

std::array<uint8_t, 3> pixel(const Image& image, int x, int y) {
  const uint8_t* p = image.at(x, y);
  return {p[0], p[1], p[2]};
}

// Two triangles splitting a w x h screen along its diagonal from (0, 0) to (w, h): triangle 0
// above it (top-right), triangle 1 below (bottom-left); the identity_warp.
WarpMesh two_triangles(int w, int h) { return identity_warp(w, h); }

TEST(Heatmap, ScaleRunsFromBlueToRedAndClamps) {
  const auto blue = heat_colour(0), red = heat_colour(1);
  EXPECT_GT(blue[2], 2 * blue[0]);
  EXPECT_GT(blue[2], 2 * blue[1]);
  EXPECT_GT(red[0], 2 * red[1]);
  EXPECT_GT(red[0], 2 * red[2]);
  EXPECT_EQ(heat_colour(-3), blue);
  EXPECT_EQ(heat_colour(7), red);
  EXPECT_EQ(heat_colour(INFINITY), red);
  // Red rises and blue falls across the scale's halves.
  EXPECT_LT(heat_colour(0.25)[0], heat_colour(0.75)[0]);
  EXPECT_GT(heat_colour(0.25)[2], heat_colour(0.75)[2]);
}

TEST(Heatmap, DrawsEachTriangleInItsColourOverGrey) {
  const WarpMesh mesh = two_triangles(40, 30);
  Image background(80, 60, 3, 100);  // twice the screen size: coordinates are scaled
  Eigen::VectorXd values(2);
  values << 0.0, 2.0;
  Eigen::Matrix<bool, Eigen::Dynamic, 1> flipped(2);
  flipped << false, false;
  const Image opaque = heatmap(mesh, values, flipped, background, 2.0, 1.0);
  ASSERT_EQ(opaque.width, 80);
  ASSERT_EQ(opaque.height, 60);
  ASSERT_EQ(opaque.channels, 3);
  EXPECT_EQ(pixel(opaque, 70, 5), heat_colour(0));  // above the diagonal
  EXPECT_EQ(pixel(opaque, 5, 55), heat_colour(1));  // below
  // Half opacity: halfway between the colour and the background's grey.
  const Image half = heatmap(mesh, values, flipped, background, 4.0, 0.5);
  const auto c = heat_colour(0.5);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(pixel(half, 5, 55)[size_t(k)], 0.5 * c[size_t(k)] + 50, 1);
  flipped << true, false;
  EXPECT_EQ(pixel(heatmap(mesh, values, flipped, background, 2.0, 1.0), 70, 5), kFlippedColour);
}

TEST(Heatmap, UncoveredPixelsKeepTheBackgroundLuminance) {
  WarpMesh mesh = two_triangles(40, 30);
  mesh.screen *= 0.5;  // covers the top-left quarter only
  Image background(40, 30, 3);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      uint8_t* p = background.at(x, y);
      p[0] = 200;
      p[1] = 100;
      p[2] = 0;
    }
  Eigen::VectorXd values = Eigen::VectorXd::Ones(2);
  Eigen::Matrix<bool, Eigen::Dynamic, 1> flipped = Eigen::Matrix<bool, Eigen::Dynamic, 1>::Zero(2);
  const Image out = heatmap(mesh, values, flipped, background, 1.0);
  const uint8_t grey = uint8_t(std::lround(0.299 * 200 + 0.587 * 100));
  EXPECT_EQ(pixel(out, 35, 25), (std::array<uint8_t, 3>{grey, grey, grey}));
  EXPECT_NE(pixel(out, 3, 12), pixel(out, 35, 25));
}

// The heat map and the renderer decide coverage by one rule: on a jittered mesh whose edges cross
// pixel centres, every pixel shows the same triangle in both (each triangle rendered in a flat
// colour of its parity, and drawn in the heat map with its parity as the value).
TEST(Heatmap, CoversEveryPixelAsTheRendererDoes) {
  const WarpMesh grid = test::grid_warp(
      9, 7, 40, 30,
      [](const Eigen::Vector2d& s) {
        // Interior vertices moved off the grid; some edges pass exactly through pixel centres.
        const bool border = s.x() == 0 || s.y() == 0 || s.x() == 40 || s.y() == 30;
        return border ? s : Eigen::Vector2d(s + Eigen::Vector2d(std::fmod(s.y(), 3.0) - 1, 0.5));
      },
      40, 30);
  // A triangle soup on the same screen, in reverse order (so that the later of two triangles
  // sharing a horizontal edge is the upper one, which the tie rule does not pick): triangle f
  // samples texel f % 2 of a 2 x 1 source.
  WarpMesh soup;
  soup.screen_width = 40;
  soup.screen_height = 30;
  soup.F.resize(grid.F.rows(), 3);
  soup.screen.resize(3 * grid.F.rows(), 2);
  soup.source.resize(3 * grid.F.rows(), 2);
  for (Eigen::Index f = 0; f < grid.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      soup.F(f, k) = int(3 * f + k);
      soup.screen.row(3 * f + k) = grid.screen.row(grid.F(grid.F.rows() - 1 - f, k));
      soup.source.row(3 * f + k) = Eigen::RowVector2d(f % 2 + 0.5, 0.5);
    }
  Image source(2, 1, 3);
  std::fill_n(source.at(0, 0), 3, uint8_t(0));
  std::fill_n(source.at(1, 0), 3, uint8_t(255));
  RenderOptions options;
  options.width = 40;
  options.height = 30;
  options.background = {128, 128, 128, 255};
  const Image rendered = render(soup, MipPyramid(source), options);
  Eigen::VectorXd values(grid.F.rows());
  for (Eigen::Index f = 0; f < values.size(); ++f) values(f) = double(f % 2);
  const Eigen::Matrix<bool, Eigen::Dynamic, 1> flipped =
      Eigen::Matrix<bool, Eigen::Dynamic, 1>::Zero(grid.F.rows());
  const Image heat = heatmap(soup, values, flipped, Image(40, 30, 3, 128), 1.0, 1.0);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      const uint8_t r = rendered.at(x, y)[0];
      ASSERT_TRUE(r == 0 || r == 255) << "uncovered pixel " << x << ", " << y;
      EXPECT_EQ(pixel(heat, x, y), heat_colour(r == 255 ? 1.0 : 0.0)) << x << ", " << y;
    }
}

TEST(Heatmap, LegendAddsAStripWithTheScale) {
  const Image image(300, 200, 3, 77);
  const Image out = with_legend(image, 0.45, "shape distortion");
  EXPECT_EQ(out.width, 300);
  EXPECT_GT(out.height, 200 + 24);
  for (int y = 0; y < 200; y += 17)
    for (int x = 0; x < 300; x += 13) EXPECT_EQ(pixel(out, x, y)[0], 77);
  bool has_blue = false, has_red = false, has_black = false;
  for (int y = 200; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const auto p = pixel(out, x, y);
      has_blue = has_blue || p == heat_colour(0);
      has_red = has_red || p == heat_colour(1);
      has_black = has_black || p == kFlippedColour;
    }
  EXPECT_TRUE(has_blue);
  EXPECT_TRUE(has_red);
  EXPECT_TRUE(has_black);
}

TEST(Heatmap, TextIsDrawnWithinItsWidth) {
  EXPECT_EQ(text_width("", 2), 0);
  EXPECT_GT(text_width("zoom 2.0", 1), text_width("zoom", 1));
  EXPECT_EQ(text_width("fisheye", 3), 3 * text_width("fisheye", 1));
  Image image(120, 40, 3, 255);
  draw_text(image, 10, 5, "Zoom 2", 2, {0, 0, 0});
  int inked = 0, right = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 120; ++x)
      if (pixel(image, x, y)[0] == 0) {
        ++inked;
        right = std::max(right, x);
        EXPECT_GE(x, 10);
        EXPECT_GE(y, 5);
        EXPECT_LT(y, 5 + 2 * 12);
      }
  EXPECT_GT(inked, 50);
  EXPECT_LT(right, 10 + text_width("Zoom 2", 2));
  draw_text(image, 100, 30, "clipped at the border \x01\xff", 2, {0, 0, 0});  // no crash
  Image grey(10, 10, 1);
  EXPECT_THROW(draw_text(grey, 0, 0, "x", 1, {0, 0, 0}), InvalidInput);
}

TEST(Heatmap, RejectsBadInput) {
  const WarpMesh mesh = two_triangles(10, 10);
  const Image background(10, 10, 3);
  Eigen::Matrix<bool, Eigen::Dynamic, 1> flipped = Eigen::Matrix<bool, Eigen::Dynamic, 1>::Zero(2);
  EXPECT_THROW(heatmap(mesh, Eigen::VectorXd::Zero(3), flipped, background, 1), InvalidInput);
  EXPECT_THROW(heatmap(mesh, Eigen::VectorXd::Zero(2), flipped, background, 0), InvalidInput);
  EXPECT_THROW(heatmap(mesh, Eigen::VectorXd::Zero(2), flipped, background, 1, 1.5), InvalidInput);
  EXPECT_THROW(with_legend(background, -1, "x"), InvalidInput);
}

}  // namespace
}  // namespace geolens
