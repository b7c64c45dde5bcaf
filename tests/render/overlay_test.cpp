// Features drawn over a picture: anti-aliased strokes and dots where the features are, each path
// blended once, labels upright beside their feature, and an overlay mapped through a lens lands
// on the features of the image rendered through it.

#include "geolens/render/overlay.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geolens/core/errors.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/render/render.h"
#include "geolens/warp/map_features.h"

namespace geolens {
namespace {

using Colour = std::array<uint8_t, 3>;

Geometry make(GeometryType type, Eigen::MatrixX2d path) {
  Geometry g;
  g.type = type;
  g.paths = {std::move(path)};
  return g;
}

VectorData one(Geometry g, std::string properties = "null") {
  VectorData data;
  data.features = {{std::move(g), "", std::move(properties)}};
  return data;
}

Colour at(const Image& image, int x, int y) {
  const uint8_t* p = image.at(x, y);
  return {p[0], p[1], p[2]};
}

TEST(Overlay, StrokesAreAntiAliasedAndCoverTheirWidth) {
  OverlayStyle style;
  style.label_scale = 0;
  Image image(100, 60, 3, 255);
  // A horizontal line through pixel centres of row 20.
  draw_overlay(image,
               one(make(GeometryType::kLineString,
                        (Eigen::MatrixX2d(2, 2) << 10.5, 20.5, 90.5, 20.5).finished())),
               style);
  EXPECT_EQ(at(image, 50, 20), style.line_colour);  // on the line: covered
  // One pixel away: distance 1 from a stroke of half width 1, half covered.
  for (const int y : {19, 21}) {
    const Colour c = at(image, 50, y);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(c[size_t(k)], (255 + style.line_colour[size_t(k)]) / 2.0, 1.0) << y;
    }
  }
  EXPECT_EQ(at(image, 50, 23), (Colour{255, 255, 255}));  // beyond reach
  EXPECT_EQ(at(image, 50, 17), (Colour{255, 255, 255}));
  EXPECT_EQ(at(image, 5, 20), (Colour{255, 255, 255}));  // before its start

  // A dot of radius 3.5 at a pixel centre: covered there, untouched 5 px away.
  Image dots(40, 40, 4, 0);
  draw_overlay(dots, one(make(GeometryType::kPoint, Eigen::RowVector2d(20.5, 20.5))), style);
  EXPECT_EQ(at(dots, 20, 20), style.point_colour);
  EXPECT_EQ(dots.at(20, 20)[3], 255);  // alpha raised by the coverage
  EXPECT_EQ(dots.at(25, 20)[3], 0);
  EXPECT_EQ(at(dots, 20, 25), (Colour{0, 0, 0}));
}

TEST(Overlay, APathIsBlendedOnceWhereItOverlapsItself) {
  OverlayStyle style;
  style.label_scale = 0;
  const Eigen::MatrixX2d there = (Eigen::MatrixX2d(2, 2) << 5, 5, 60, 40).finished();
  const Eigen::MatrixX2d back = (Eigen::MatrixX2d(3, 2) << 5, 5, 60, 40, 5, 5).finished();
  Image once(70, 50, 3, 200), twice(70, 50, 3, 200);
  draw_overlay(once, one(make(GeometryType::kLineString, there)), style);
  draw_overlay(twice, one(make(GeometryType::kLineString, back)), style);
  EXPECT_EQ(once.pixels, twice.pixels);
  // A closed ring's first vertex is blended once too: its pixel is exactly the line colour.
  Image ring(40, 40, 3, 255);
  Eigen::MatrixX2d square(5, 2);
  square << 10.5, 10.5, 30.5, 10.5, 30.5, 30.5, 10.5, 30.5, 10.5, 10.5;
  Geometry polygon = make(GeometryType::kPolygon, square);
  draw_overlay(ring, one(polygon), style);
  EXPECT_EQ(at(ring, 10, 10), style.line_colour);
  EXPECT_EQ(at(ring, 20, 20), (Colour{255, 255, 255}));  // a stroke, not a fill
}

TEST(Overlay, LabelsAreDrawnBesideTheirFeatureFromTheNameProperty) {
  OverlayStyle style;
  const VectorData named =
      one(make(GeometryType::kPoint, Eigen::RowVector2d(30.5, 40.5)), R"({"name":"Bern"})");
  const VectorData unnamed =
      one(make(GeometryType::kPoint, Eigen::RowVector2d(30.5, 40.5)), R"({"title":"Bern"})");
  Image with(120, 80, 3, 255), without(120, 80, 3, 255);
  draw_overlay(with, named, style);
  draw_overlay(without, unnamed, style);
  int text = 0;
  for (int y = 0; y < with.height; ++y)
    for (int x = 0; x < with.width; ++x) {
      if (at(with, x, y) == at(without, x, y)) continue;
      // Right of the dot, about its height.
      EXPECT_GT(x, 30 + 3) << x << "," << y;
      EXPECT_LT(std::abs(y - 40), 7 * style.label_scale) << x << "," << y;
      text += at(with, x, y) == style.label_colour;
    }
  EXPECT_GT(text, 20);
  // Another property, and no labels at all.
  style.label_property = "title";
  Image titled(120, 80, 3, 255);
  draw_overlay(titled, unnamed, style);
  EXPECT_EQ(titled.pixels, with.pixels);
  style.label_scale = 0;
  Image plain(120, 80, 3, 255);
  draw_overlay(plain, named, style);
  EXPECT_EQ(plain.pixels, without.pixels);
}

TEST(Overlay, RefusesWhatItCannotDraw) {
  const VectorData data = one(make(GeometryType::kPoint, Eigen::RowVector2d(1, 1)));
  Image grey(10, 10, 1, 0);
  EXPECT_THROW(draw_overlay(grey, data), InvalidInput);
  Image rgb(10, 10, 3, 0);
  OverlayStyle style;
  style.line_width = 0;
  EXPECT_THROW(draw_overlay(rgb, data, style), InvalidInput);
  style = {};
  style.point_radius = std::numeric_limits<double>::infinity();
  EXPECT_THROW(draw_overlay(rgb, data, style), InvalidInput);
  style = {};
  style.label_scale = -1;
  EXPECT_THROW(draw_overlay(rgb, data, style), InvalidInput);
  VectorData bad = one(make(GeometryType::kLineString, Eigen::RowVector2d(1, 1)));
  EXPECT_THROW(draw_overlay(rgb, bad), InvalidInput);
  // Far outside the image: clipped, nothing drawn, no failure.
  const Image before = rgb;
  draw_overlay(rgb, one(make(GeometryType::kLineString,
                             (Eigen::MatrixX2d(2, 2) << -1e12, -1e12, -1e11, 5e11).finished())));
  EXPECT_EQ(rgb.pixels, before.pixels);
}

// The issue's measure: the mapped position of a source pixel of a feature is that feature's pixel
// in the magnified output. Dark marks on a white source, in and around a lens; each mark's centre
// mapped forward lands on a dark pixel of the output.
TEST(Overlay, MappedFeaturesLandOnTheMagnifiedImage) {
  const int width = 400, height = 300;
  Image source(width, height, 3, 255);
  const std::vector<Eigen::Vector2d> marks = {{200, 150}, {215, 160}, {180, 140}, {240, 150},
                                              {200, 195}, {60, 60},   {330, 250}};
  for (const Eigen::Vector2d& m : marks)
    for (int y = int(m.y()) - 2; y <= int(m.y()) + 2; ++y)
      for (int x = int(m.x()) - 2; x <= int(m.x()) + 2; ++x)
        std::fill_n(source.at(x, y), 3, uint8_t(0));
  const LensResult lens =
      GeometricLens(width, height).solve({Lens{Region::circle({200, 150}, 40), 2.5}});
  RenderOptions options;
  options.width = 600;  // a different output size: the overlay is framed as the render is
  options.height = 450;
  const Image output = render(lens.warp, MipPyramid(source), options);
  WarpMesh framed = lens.warp;
  framed.screen.col(0) *= 600.0 / framed.screen_width;
  framed.screen.col(1) *= 450.0 / framed.screen_height;
  framed.screen_width = 600;
  framed.screen_height = 450;
  const WarpMap map(framed);
  for (const Eigen::Vector2d& m : marks) {
    // The centre of the mark's middle pixel.
    const Eigen::Vector2d q = *map.forward(m + Eigen::Vector2d(0.5, 0.5));
    EXPECT_LT(output.at(int(q.x()), int(q.y()))[0], 60) << m.transpose() << " -> " << q.transpose();
  }
}

}  // namespace
}  // namespace geolens
