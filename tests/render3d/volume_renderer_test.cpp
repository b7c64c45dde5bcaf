// The transfer function (linear between control points, constant beyond; tables and presets)
// and the volume ray caster: a constant volume shows its colour at the opacity its thickness
// compounds, per voxel of the smallest spacing and whatever the step; rays that miss the box show
// the background; the nearer of two opaque halves hides the farther; skipping empty blocks
// changes no pixel; a region is the same pixels as the full render's; bad input is refused.

#include "render3d/volume_renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "core/thread_pool.h"
#include "geolens/core/errors.h"
#include "render3d/transfer_function.h"
#include "support/refusal.h"
#include "support/scratch_folder.h"

namespace geolens {
namespace {

/// An nx x ny x nz volume of `spacing` whose voxel (i, j, k) is value(i, j, k).
template <typename Value>
ScalarVolume volume_of(int nx, int ny, int nz, Eigen::Vector3d spacing, Value value) {
  ScalarVolume v;
  v.nx = nx;
  v.ny = ny;
  v.nz = nz;
  v.spacing = spacing;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) v.values.push_back(float(value(i, j, k)));
  return v;
}

OrbitCamera front_camera() {
  OrbitCamera camera;
  camera.azimuth_degrees = 0;
  camera.elevation_degrees = 0;
  return camera;
}

TEST(TransferFunction, InterpolatesLinearlyBetweenPointsAndHoldsBeyondTheEnds) {
  const TransferFunction tf({{-10, {0, 0, 0}, 0}, {10, {1, 0.5, 0}, 0.8}, {20, {0, 0, 1}, 1}});
  using Rgba = std::array<double, 4>;
  EXPECT_EQ(tf(-1000), (Rgba{0, 0, 0, 0}));
  EXPECT_EQ(tf(-10), (Rgba{0, 0, 0, 0}));
  EXPECT_EQ(tf(0), (Rgba{0.5, 0.25, 0, 0.4}));
  EXPECT_EQ(tf(10), (Rgba{1, 0.5, 0, 0.8}));
  const Rgba between = tf(17.5);
  EXPECT_NEAR(between[0], 0.25, 1e-12);
  EXPECT_NEAR(between[2], 0.75, 1e-12);
  EXPECT_NEAR(between[3], 0.95, 1e-12);
  EXPECT_EQ(tf(1e9), (Rgba{0, 0, 1, 1}));
  const TransferFunction one({{5, {0.2, 0.4, 0.6}, 0.3}});  // a single point: constant
  EXPECT_EQ(one(-1e9), one(1e9));
  EXPECT_EQ(one(0)[3], 0.3);
}

using TransferTable = testing::ScratchFolderTest;

TEST_F(TransferTable, TablesAndPresetsAreReadAndBadOnesRefusedNamingTheLine) {
  std::ofstream(path("ok.tf")) << "# value R G B opacity\n\n-5 0 0 0 0\n  # indented comment\n"
                                  "5 255 51 0 0.5\n";
  const TransferFunction table = load_transfer_table(path("ok.tf"));
  ASSERT_EQ(table.points().size(), 2u);
  EXPECT_EQ(table(5), (std::array<double, 4>{1, 0.2, 0, 0.5}));  // RGB / 255
  EXPECT_EQ(transfer_function(path("ok.tf"), ScalarVolume{}).points().size(), 2u);
  auto table_refusal = [&](const std::string& text) {
    std::ofstream(path("bad.tf")) << text;
    return test::refusal([&] { load_transfer_table(path("bad.tf")); });
  };
  EXPECT_NE(
      table_refusal("0 0 0 0 0\n\n0 1 1 1 1\n")
          .find("load_transfer_table: '" + path("bad.tf") + "' line 3: the values must increase"),
      std::string::npos);
  EXPECT_NE(table_refusal("0 0 0 0 1.5\n").find("line 1: an opacity outside [0, 1]"),
            std::string::npos);
  EXPECT_NE(table_refusal("0 0 300 0 1\n").find("line 1: a colour outside [0, 255]"),
            std::string::npos);
  EXPECT_NE(table_refusal("0 0 0 0\n").find("line 1: expected 'VALUE R G B OPACITY'"),
            std::string::npos);
  EXPECT_NE(table_refusal("# only\n").find("no control point"), std::string::npos);
  EXPECT_NE(test::refusal([] {
              TransferFunction({{1, {0, 0, 0}, 0}, {1, {0, 0, 0}, 0}});
            }).find("point 1: the values must be finite and increasing"),
            std::string::npos);
  EXPECT_NE(test::refusal([] {
              TransferFunction({{1, {0, 2, 0}, 0}});
            }).find("outside [0, 1]"),
            std::string::npos);
  // The empty spec picks "ct" for Hounsfield values (some below -200), "mri" otherwise, whose
  // last point is the 99th percentile (here 100, of the values 1 ... 100).
  const ScalarVolume ct = volume_of(10, 10, 1, {1, 1, 1},
                                    [](int i, int j, int) { return i + 10 * j == 0 ? -1000 : 40; });
  const ScalarVolume mri =
      volume_of(10, 10, 1, {1, 1, 1}, [](int i, int j, int) { return 1 + i + 10 * j; });
  EXPECT_EQ(transfer_function("", ct).points().size(), transfer_preset("ct", ct).points().size());
  const TransferFunction picked = transfer_function("", mri);
  EXPECT_EQ(picked.points().size(), 5u);
  EXPECT_EQ(picked.points().back().value, 100);
  EXPECT_NE(test::refusal([&] { transfer_function("bone", mri); }).find("unknown transfer 'bone'"),
            std::string::npos);
}

// A 4-voxel-thick constant volume seen straight along z: the ray through the frame's centre
// crosses 4 voxels of opacity a each (8 with 2-unit slices, opacity being per voxel of the
// smallest spacing), so it is 1 - (1 - a)^n opaque, whatever the step; pure red over a blue
// background. A frame corner's ray misses the box: the background, exactly.
TEST(VolumeRenderer, AConstantVolumeShowsItsColourAtTheOpacityItsThicknessCompounds) {
  const double a = 0.2;
  const TransferFunction red({{0, {1, 0, 0}, a}});
  VolumeStyle style;
  style.shading = false;
  style.opaque = 1;
  style.background = {0, 0, 255};
  const int side = 33;  // odd: the middle pixel's ray is the axis
  struct Case {
    double slice, step;
    int voxels;  // crossed along z, in units of the smallest spacing
  };
  for (const Case c : {Case{1, 0.5, 4}, Case{1, 0.25, 4}, Case{1, 1, 4}, Case{2, 0.5, 8}}) {
    style.step = c.step;
    const VolumeRenderer renderer(
        volume_of(4, 4, 4, {1, 1, c.slice}, [](int, int, int) { return 7; }), red, front_camera(),
        side, side, style);
    const Image image = renderer.render({1, 0, 0, side, side});
    const double alpha = 1 - std::pow(1 - a, c.voxels);
    const uint8_t* middle = image.at(side / 2, side / 2);
    EXPECT_NEAR(middle[0], 255 * alpha, 1) << "slice " << c.slice << ", step " << c.step;
    EXPECT_EQ(middle[1], 0);
    EXPECT_NEAR(middle[2], 255 * (1 - alpha), 1) << "slice " << c.slice << ", step " << c.step;
    for (const auto& [x, y] : {std::pair{0, 0}, {side - 1, 0}, {0, side - 1}, {side - 1, side - 1}})
      EXPECT_EQ(std::vector<uint8_t>(image.at(x, y), image.at(x, y) + 3),
                (std::vector<uint8_t>{0, 0, 255}))
          << x << ", " << y;
  }
}

// Front to back: two opaque halves, green at high z and red at low z. From +z (azimuth 0) the
// green half is in front; from -z (azimuth 180) the red one.
TEST(VolumeRenderer, TheNearerOfTwoOpaqueHalvesHidesTheFarther) {
  const ScalarVolume halves =
      volume_of(8, 8, 8, {1, 1, 1}, [](int, int, int k) { return k >= 4 ? 2 : 1; });
  const TransferFunction tf({{1, {1, 0, 0}, 1}, {2, {0, 1, 0}, 1}});
  VolumeStyle style;
  style.shading = false;
  const int side = 21;
  for (const double azimuth : {0.0, 180.0}) {
    OrbitCamera camera = front_camera();
    camera.azimuth_degrees = azimuth;
    const VolumeRenderer renderer(halves, tf, camera, side, side, style);
    const uint8_t* middle = renderer.render({1, 0, 0, side, side}).at(side / 2, side / 2);
    const int near = azimuth == 0 ? 1 : 0, far = 1 - near;  // channel of the nearer half
    EXPECT_GT(middle[near], 240) << "azimuth " << azimuth;
    EXPECT_LT(middle[far], 15) << "azimuth " << azimuth;
  }
}

/// A 24^3 volume of zeros with a 3^3 block of ones (voxels 11 - 13 along x and y, 19 - 21 along
/// z), its non-zero samples away from the borders of the renderer's 8^3 blocks.
ScalarVolume blob() {
  return volume_of(24, 24, 24, {1, 1, 1}, [](int i, int j, int k) {
    return i >= 11 && i <= 13 && j >= 11 && j <= 13 && k >= 19 && k <= 21 ? 1 : 0;
  });
}

// With zero transparent (opacity 0 at value 0), the renderer skips every empty block; with a
// faint 1e-7 opacity there, nothing is skipped. The blob shows, and the pictures agree to the
// rounding of that faint haze.
TEST(VolumeRenderer, SkippingEmptyBlocksChangesNoPixel) {
  const TransferFunction skipped({{0, {0, 0, 0}, 0}, {1, {1, 0.5, 0}, 1}});
  const TransferFunction unskipped({{0, {0, 0, 0}, 1e-7}, {1, {1, 0.5, 0}, 1}});
  VolumeStyle style;
  style.background = {255, 255, 255};  // so that any opacity a ray gains or loses shows
  const int side = 48;
  const Image a = VolumeRenderer(blob(), skipped, OrbitCamera{}, side, side, style)
                      .render({1, 0, 0, side, side});
  const Image b = VolumeRenderer(blob(), unskipped, OrbitCamera{}, side, side, style)
                      .render({1, 0, 0, side, side});
  int differ = 0, blob_pixels = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    differ += std::abs(int(a.pixels[i]) - int(b.pixels[i])) > 1;
    blob_pixels += i % 3 == 2 && a.pixels[i] < 200;  // the blob absorbs blue
  }
  EXPECT_EQ(differ, 0);
  EXPECT_GT(blob_pixels, 10);
}

TEST(VolumeRenderer, ARegionIsTheSamePixelsAsTheFullRenderOnOneThreadOrMany) {
  const ScalarVolume ramp = volume_of(
      12, 10, 9, {1, 1.5, 1}, [](int i, int j, int k) { return std::hypot(i - 6, j - 5, k - 4); });
  const TransferFunction tf({{0, {1, 1, 1}, 0.6}, {4, {1, 0.3, 0.1}, 0.1}, {6, {0, 0, 1}, 0}});
  const VolumeRenderer renderer(ramp, tf, OrbitCamera{}, 40, 30);
  const Image full = renderer.render({0.5, 0, 0, 80, 60});
  for (const PixelRegion region : {PixelRegion{0.5, 17, 11, 40, 30}, PixelRegion{0.5, 0, 7, 80, 1},
                                   PixelRegion{0.5, 79, 0, 1, 60}}) {
    const Image part = renderer.render(region);
    int differ = 0;
    for (int j = 0; j < region.height; ++j)
      for (int i = 0; i < region.width; ++i)
        for (int c = 0; c < 3; ++c)
          differ += part.at(i, j)[c] != full.at(region.x + i, region.y + j)[c];
    EXPECT_EQ(differ, 0) << region.x << ", " << region.y;
  }
  ThreadPool pool(2);
  EXPECT_EQ(renderer.render({0.5, 0, 0, 80, 60}, &pool).pixels, full.pixels);
  const auto [lo, hi] = std::minmax_element(full.pixels.begin(), full.pixels.end());
  EXPECT_EQ(*lo, 0);    // background
  EXPECT_GT(*hi, 150);  // and the volume
}

TEST(VolumeRenderer, RefusesBadVolumesStylesAndRegions) {
  const TransferFunction tf({{0, {1, 1, 1}, 0.5}});
  const ScalarVolume good = volume_of(2, 2, 2, {1, 1, 1}, [](int, int, int) { return 1; });
  auto refused = [&](const ScalarVolume& volume, const VolumeStyle& style) {
    return test::refusal([&] { VolumeRenderer(volume, tf, OrbitCamera{}, 10, 10, style); });
  };
  VolumeStyle no_step, long_step, never_opaque, no_light;
  no_step.step = 0;
  long_step.step = 4.5;
  never_opaque.opaque = 0;
  no_light.light = Eigen::Vector3d::Zero();
  ScalarVolume short_values = good, flat = good, bad_value = good;
  short_values.values.pop_back();
  flat.spacing.z() = 0;
  bad_value.values[3] = NAN;
  const std::pair<std::string, std::string> cases[] = {
      {refused(good, no_step), "step 0.000000 is not in (0, 4]"},
      {refused(good, long_step), "step 4.500000 is not in (0, 4]"},
      {refused(good, never_opaque), "opaque must be in (0, 1]"},
      {refused(good, no_light), "the light direction is zero"},
      {refused(short_values, {}), "7 values for 2 x 2 x 2"},
      {refused(flat, {}), "spacing must be finite and positive"},
      {refused(bad_value, {}), "a voxel value is not finite"},
  };
  for (const auto& [message, what] : cases) {
    EXPECT_EQ(message.rfind("VolumeRenderer: ", 0), 0u) << message;
    EXPECT_NE(message.find(what), std::string::npos) << what << "\n" << message;
  }
  const VolumeRenderer renderer(good, tf, OrbitCamera{}, 10, 10);
  EXPECT_NE(test::refusal([&] {
              renderer.render({1, 0, 0, 3, 0});
            }).find("VolumeRenderer::render: region 3 x 0"),
            std::string::npos);
}

}  // namespace
}  // namespace geolens
