// The mesh renderer: a triangle covers exactly the pixels whose centres its projection covers
// and leaves the background elsewhere, at any pixel size and region offset; the nearer of two
// overlapping faces shows whatever their order; supersampling averages a pixel an edge halves;
// a region is the same pixels as the full render's, in one band or many, on one thread or a pool;
// bad meshes, styles and regions are refused.

#include "render3d/mesh_renderer.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "core/thread_pool.h"
#include "geolens/core/errors.h"
#include "support/refusal.h"

namespace geolens {
namespace {

/// A camera on the model's +z axis looking down -z, model x to the right and y up.
OrbitCamera front_camera() {
  OrbitCamera camera;
  camera.azimuth_degrees = 0;
  camera.elevation_degrees = 0;
  return camera;
}

/// A style whose surface is black (with no highlight) on white, one sample per pixel: a pixel
/// is 0 where a triangle covers its centre and 255 elsewhere.
MeshStyle black_on_white() {
  MeshStyle style;
  style.colour = {0, 0, 0};
  style.specular = 0;
  style.samples = 1;
  return style;
}

/// The pixels of `image` in the block of `width` x `height` at (x, y).
Image crop(const Image& image, int x, int y, int width, int height) {
  Image out(width, height, image.channels);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i)
      for (int c = 0; c < image.channels; ++c) out.at(i, j)[c] = image.at(x + i, y + j)[c];
  return out;
}

/// Twice the signed area of (a, b, p): > 0 when p is left of a -> b in a y-down frame.
double side(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
}

TEST(MeshRenderer, ATriangleCoversThePixelsWhoseCentresItsProjectionCovers) {
  TriangleMesh mesh;
  mesh.V.resize(3, 3);
  mesh.V << -1, -0.8, 0, 1.1, -0.3, 0.4, -0.2, 1, -0.5;  // tilted: perspective matters
  mesh.F.resize(1, 3);
  mesh.F << 0, 1, 2;
  const int width = 90, height = 70;
  const MeshRenderer renderer(mesh, front_camera(), width, height, black_on_white());
  const Projection& p = renderer.projection();
  Eigen::Vector2d corner[3];
  for (int k = 0; k < 3; ++k) corner[k] = p.project(p.to_camera(mesh.V.row(k).transpose()));
  // The whole frame at 1 frame pixel per pixel, and a region of a grid of half pixels.
  for (const PixelRegion region :
       {PixelRegion{1, 0, 0, width, height}, PixelRegion{0.5, 40, 30, 90, 80}}) {
    const Image image = renderer.render(region);
    int covered = 0, wrong = 0;
    for (int j = 0; j < region.height; ++j)
      for (int i = 0; i < region.width; ++i) {
        const Eigen::Vector2d centre((region.x + i + 0.5) * region.pixel_size,
                                     (region.y + j + 0.5) * region.pixel_size);
        double margin = INFINITY, sign = 0;
        for (int k = 0; k < 3; ++k) {
          const double s = side(corner[k], corner[(k + 1) % 3], centre);
          margin = std::min(margin, std::abs(s) / (corner[(k + 1) % 3] - corner[k]).norm());
          sign += s > 0 ? 1 : -1;
        }
        if (margin < 1e-6) continue;  // on an edge: the tie rule decides
        const bool inside = std::abs(sign) == 3;
        const uint8_t* pixel = image.at(i, j);
        covered += inside;
        if (inside ? pixel[0] != 0 : (pixel[0] != 255 || pixel[1] != 255 || pixel[2] != 255))
          ++wrong;
      }
    EXPECT_EQ(wrong, 0) << "pixel size " << region.pixel_size;
    EXPECT_GT(covered, 500) << "pixel size " << region.pixel_size;
  }
}

/// Square A, [-1, 1]^2 at z = 0, facing the camera; square B, 1 wide, tilted 60 degrees about
/// the x axis (so a light from the camera shows it at half brightness), centred on the axis at
/// z = `b_depth`; B's faces first in F when `b_first`.
TriangleMesh two_squares(double b_depth, bool b_first) {
  const double c = std::cos(M_PI / 3) / 2, s = std::sin(M_PI / 3) / 2;
  TriangleMesh mesh;
  mesh.V.resize(8, 3);
  mesh.V << -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0,  // A
      -0.5, -c, b_depth - s, 0.5, -c, b_depth - s, 0.5, c, b_depth + s, -0.5, c, b_depth + s;
  Eigen::MatrixXi a(2, 3), b(2, 3);
  a << 0, 1, 2, 0, 2, 3;
  b << 4, 5, 6, 4, 6, 7;
  mesh.F.resize(4, 3);
  mesh.F << (b_first ? b : a), (b_first ? a : b);
  return mesh;
}

TEST(MeshRenderer, TheNearerOfTwoOverlappingFacesShowsWhateverTheirOrder) {
  MeshStyle style;
  style.shading = MeshShading::flat;
  style.colour = {200, 200, 200};
  style.light = {0, 0, 1};  // from the camera: brightness = cos(the face's tilt)
  style.ambient = 0;
  style.diffuse = 1;
  style.specular = 0;
  style.samples = 1;
  const int side = 41;  // odd: the middle pixel's centre is on the axis
  for (const bool b_first : {false, true}) {
    for (const double b_depth : {0.6, -0.6}) {
      const MeshRenderer renderer(two_squares(b_depth, b_first), front_camera(), side, side, style);
      const Image image = renderer.render({1, 0, 0, side, side});
      const int expected = b_depth > 0 ? 100 : 200;  // B in front, tilted; else A, facing
      EXPECT_NEAR(image.at(side / 2, side / 2)[0], expected, 1)
          << "B at z = " << b_depth << (b_first ? ", first" : ", last");
      // A's corner region, outside B's projection, shows A either way.
      const Projection& p = renderer.projection();
      const Eigen::Vector2d a_only = p.project(p.to_camera({0.85, 0.85, 0}));
      EXPECT_NEAR(image.at(int(a_only.x()), int(a_only.y()))[0], 200, 1);
    }
  }
}

// An edge through the middle of a pixel column: of its 2 x 2 samples, the left two are on the
// surface (black) and the right two on the background (white), so the pixel is the mean.
TEST(MeshRenderer, SupersamplingAveragesAPixelAnEdgeCutsInHalf) {
  TriangleMesh mesh;
  mesh.V.resize(5, 3);
  mesh.V << -1, -1, 0, 0, -1, 0, 0, 1, 0, -1, 1, 0, 1, 0, 0;  // [-1, 0] x [-1, 1], and (1, 0, 0)
  mesh.F.resize(3, 3);
  mesh.F << 0, 1, 2, 0, 2, 3, 4, 4, 4;  // a degenerate face widens the bounding box to x = 1
  MeshStyle style = black_on_white();
  style.samples = 2;
  const int side = 41;  // model x = 0 projects to frame x 20.5, the middle of column 20
  const MeshRenderer renderer(mesh, front_camera(), side, side, style);
  const Image image = renderer.render({1, 0, 0, side, side});
  for (const int row : {15, 20, 25}) {
    EXPECT_EQ(image.at(19, row)[0], 0) << row;
    EXPECT_EQ(image.at(20, row)[0], 128) << row;  // (0 + 255) / 2, rounded
    EXPECT_EQ(image.at(21, row)[0], 255) << row;
  }
}

/// A cube [-1, 1]^3 of 12 triangles, counter-clockwise from outside.
TriangleMesh cube() {
  TriangleMesh mesh;
  mesh.V.resize(8, 3);
  mesh.V << -1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1;
  mesh.F.resize(12, 3);
  mesh.F << 0, 3, 2, 0, 2, 1, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6,
      5, 0, 4, 7, 0, 7, 3;
  return mesh;
}

// Regions start anywhere in the grid and rows split into bands of 32: every region of the grid
// is the same pixels as the full render's, and a pool's bands are the serial ones.
TEST(MeshRenderer, ARegionIsTheSamePixelsAsTheFullRenderOnOneThreadOrMany) {
  MeshStyle style;
  style.edges = true;
  style.samples = 3;
  const MeshRenderer renderer(cube(), OrbitCamera{}, 60, 50, style);
  const Image full = renderer.render({0.5, 0, 0, 120, 100});
  const auto [lo, hi] = std::minmax_element(full.pixels.begin(), full.pixels.end());
  EXPECT_LT(*lo, 100);  // edges and shade are there
  EXPECT_EQ(*hi, 255);  // and the background
  for (const PixelRegion region :
       {PixelRegion{0.5, 13, 37, 70, 45}, PixelRegion{0.5, 0, 31, 120, 3},
        PixelRegion{0.5, 101, 0, 19, 100}}) {
    EXPECT_EQ(renderer.render(region).pixels,
              crop(full, region.x, region.y, region.width, region.height).pixels)
        << region.x << ", " << region.y;
  }
  ThreadPool pool(2);
  EXPECT_EQ(renderer.render({0.5, 0, 0, 120, 100}, &pool).pixels, full.pixels);
}

TEST(MeshRenderer, RefusesBadMeshesStylesAndRegions) {
  auto refused = [](const TriangleMesh& mesh, const MeshStyle& style) {
    return test::refusal([&] { MeshRenderer(mesh, OrbitCamera{}, 10, 10, style); });
  };
  const MeshStyle good;
  MeshStyle no_samples, many_samples, dark, no_light;
  no_samples.samples = 0;
  many_samples.samples = 9;
  dark.ambient = -0.1;
  no_light.light = Eigen::Vector3d::Zero();
  TriangleMesh empty = cube(), outside = cube(), infinite = cube();
  empty.F.resize(0, 3);
  outside.F(3, 1) = 8;
  infinite.V(2, 0) = INFINITY;
  const std::pair<std::string, std::string> cases[] = {
      {refused(cube(), no_samples), "samples 0 is not in [1, 8]"},
      {refused(cube(), many_samples), "samples 9 is not in [1, 8]"},
      {refused(cube(), dark), "negative"},
      {refused(cube(), no_light), "the light direction is zero"},
      {refused(empty, good), "the mesh has no triangle"},
      {refused(outside, good), "face 3 names vertex 8, outside [0, 8)"},
      {refused(infinite, good), "not finite"},
  };
  for (const auto& [message, what] : cases) {
    EXPECT_EQ(message.rfind("MeshRenderer: ", 0), 0u) << message;
    EXPECT_NE(message.find(what), std::string::npos) << what << "\n" << message;
  }
  const MeshRenderer renderer(cube(), OrbitCamera{}, 10, 10);
  EXPECT_NE(test::refusal([&] {
              renderer.render({1, 0, 0, 0, 10});
            }).find("MeshRenderer::render: region 0 x 10"),
            std::string::npos);
  EXPECT_NE(test::refusal([&] {
              renderer.render({-1, 0, 0, 4, 4});
            }).find("pixel size"),
            std::string::npos);
}

}  // namespace
}  // namespace geolens
