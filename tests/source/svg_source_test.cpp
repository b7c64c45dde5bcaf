// The SVG source: its frame maps the SVG's extent as documented, its finer levels are drawn at
// their own resolution (crisper than the frame level upsampled), malformed files are refused.

#include "source/svg_source.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/render/render.h"
#include "geolens/source/source.h"
#include "geolens/source/source_file.h"
#include "geolens/warp/warp_mesh.h"
#include "support/scratch_folder.h"

using geolens::Image;
using geolens::InvalidInput;
using geolens::SourceFile;
using geolens::SourceFileOptions;
using geolens::TexelRegion;
using geolens::WarpMesh;

namespace {

using SvgSourceTest = geolens::testing::ScratchFolderTest;

/// 432 x 360 pt (576 x 480 CSS px), user units = pt: a black rectangle at x [36, 108], y [30, 90].
const char* kRectangleSvg = R"(<?xml version="1.0"?>
<svg xmlns="http://www.w3.org/2000/svg" width="432pt" height="360pt" viewBox="0 0 432 360">
  <rect x="36" y="30" width="72" height="60" fill="black"/>
</svg>
)";

/// 64 x 64 px: thin lines and a circle, whose edges need the finer levels when magnified.
const char* kLinesSvg = R"(<svg xmlns="http://www.w3.org/2000/svg" width="64" height="64">
  <path d="M 3 5 L 60 40 M 5 60 L 50 2 M 10 30 L 62 33" stroke="black" stroke-width="0.4"/>
  <circle cx="32" cy="32" r="17.3" fill="none" stroke="black" stroke-width="0.7"/>
</svg>)";

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// The frame as a lens-free render draws it: the identity at the frame's size.
Image render_frame(const SourceFile& file, int threads = 1) {
  geolens::RenderOptions options;
  options.width = file.frame_width;
  options.height = file.frame_height;
  options.source_scale = file.scale;
  options.threads = threads;
  return geolens::render(geolens::identity_warp(file.frame_width, file.frame_height), *file.source,
                         options);
}

int grey(const Image& image, int x, int y) { return image.at(x, y)[0]; }

/// Sum of squared differences between horizontal and vertical neighbours of the first channel.
double gradient_energy(const std::vector<double>& v, int width, int height) {
  double e = 0;
  for (int y = 0; y + 1 < height; ++y)
    for (int x = 0; x + 1 < width; ++x) {
      const double c = v[size_t(y) * width + x];
      e += std::pow(v[size_t(y) * width + x + 1] - c, 2) +
           std::pow(v[size_t(y + 1) * width + x] - c, 2);
    }
  return e;
}

double mean_absolute_difference(const Image& a, const Image& b) {
  double sum = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) sum += std::abs(a.pixels[i] - b.pixels[i]);
  return sum / double(a.pixels.size());
}

double image_gradient_energy(const Image& image) {
  std::vector<double> v;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) v.push_back(image.at(x, y)[0]);
  return gradient_energy(v, image.width, image.height);
}

std::vector<double> first_channel(const TexelRegion& r) {
  std::vector<double> v;
  for (int y = 0; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x) v.push_back(r.at(r.x + x, r.y + y)[0]);
  return v;
}

TEST_F(SvgSourceTest, SizeFramesTheWholeExtent) {
  write_text(path("a.svg"), kRectangleSvg);
  SourceFileOptions options;
  options.width = 1024;
  options.height = 854;
  const SourceFile file = geolens::open_svg(path("a.svg"), options);
  EXPECT_EQ(file.kind, "svg");
  EXPECT_EQ(file.frame_width, 1024);
  EXPECT_EQ(file.frame_height, 854);
  EXPECT_EQ(file.scale, 8.0);
  EXPECT_EQ(file.source->width(), 1024 * 8);
  EXPECT_EQ(file.source->height(), 854 * 8);
  EXPECT_EQ(file.source->channels(), 3);

  // The rectangle spans x [36, 108] / 432 * 1024 = [85.3, 256], y [30, 90] / 360 * 854 =
  // [71.2, 213.5] of the frame.
  const Image frame = render_frame(file);
  for (auto [x, y] : {std::pair{88, 74}, {253, 74}, {88, 210}, {253, 210}, {170, 140}})
    EXPECT_LT(grey(frame, x, y), 40) << x << ", " << y;
  for (auto [x, y] : {std::pair{82, 140}, {259, 140}, {170, 68}, {170, 217}, {512, 427}})
    EXPECT_GT(grey(frame, x, y), 215) << x << ", " << y;
}

TEST_F(SvgSourceTest, WithoutSizeTheFrameIsTheIntrinsicSizeInCssPixels) {
  write_text(path("a.svg"), kRectangleSvg);
  const SourceFile file = geolens::open_source(path("a.svg"));
  EXPECT_EQ(file.kind, "svg");
  EXPECT_EQ(file.frame_width, 576);  // 432 pt at 96 px per 72 pt
  EXPECT_EQ(file.frame_height, 480);
  // Only a width: the height keeps the aspect.
  SourceFileOptions options;
  options.width = 288;
  const SourceFile half = geolens::open_svg(path("a.svg"), options);
  EXPECT_EQ(half.frame_height, 240);
  // The rectangle at x [48, 144], y [40, 120] of the 576 x 480 frame.
  const Image frame = render_frame(file);
  EXPECT_LT(grey(frame, 50, 42), 40);
  EXPECT_LT(grey(frame, 141, 117), 40);
  EXPECT_GT(grey(frame, 46, 80), 215);
  EXPECT_GT(grey(frame, 146, 80), 215);
}

TEST_F(SvgSourceTest, FinestLevelIsCrisperThanTheFrameUpsampled) {
  // Thin lines and a circle: at zoom 8 their edges must come from level 0, drawn at 8x.
  write_text(path("lines.svg"), kLinesSvg);
  const SourceFile file = geolens::open_svg(path("lines.svg"));
  ASSERT_EQ(file.frame_width, 64);
  const TexelRegion fine = file.source->fetch(0, 0, 0, 512, 512);
  const TexelRegion coarse = file.source->fetch(3, 0, 0, 64, 64);
  // Level 3 upsampled 8x bilinearly, texel centres at ((i + 0.5) 8 - 0.5).
  std::vector<double> up(512 * 512);
  const std::vector<double> c = first_channel(coarse);
  for (int y = 0; y < 512; ++y)
    for (int x = 0; x < 512; ++x) {
      const double u = std::clamp((x + 0.5) / 8 - 0.5, 0.0, 63.0);
      const double v = std::clamp((y + 0.5) / 8 - 0.5, 0.0, 63.0);
      const int i = std::min(int(u), 62), j = std::min(int(v), 62);
      const double a = u - i, b = v - j;
      up[size_t(y) * 512 + x] = (1 - a) * (1 - b) * c[j * 64 + i] +
                                a * (1 - b) * c[j * 64 + i + 1] +
                                (1 - a) * b * c[(j + 1) * 64 + i] + a * b * c[(j + 1) * 64 + i + 1];
    }
  const double sharp = gradient_energy(first_channel(fine), 512, 512);
  const double blurred = gradient_energy(up, 512, 512);
  EXPECT_GT(sharp, 4 * blurred) << sharp << " vs " << blurred;
  // Both show the same picture: the mean darkness agrees within 10%.
  const auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += 255 - x;
    return s / v.size();
  };
  EXPECT_NEAR(mean(first_channel(fine)), mean(up), 0.1 * mean(up));
}

TEST_F(SvgSourceTest, MagnifiedThreeTimesItIsCloseToRasterizingAtThreeTimes) {
  write_text(path("lines.svg"), kLinesSvg);
  const SourceFile one = geolens::open_svg(path("lines.svg"));
  SourceFileOptions options;
  options.width = options.height = 192;
  const SourceFile direct_source = geolens::open_svg(path("lines.svg"), options);
  // A uniform zoom 3: the 64 x 64 frame onto 192 x 192 pixels.
  WarpMesh zoom = geolens::identity_warp(64, 64);
  zoom.screen *= 3;
  zoom.screen_width = zoom.screen_height = 192;
  geolens::RenderOptions render_options;
  render_options.width = render_options.height = 192;
  render_options.source_scale = one.scale;
  render_options.threads = 1;
  const Image magnified = geolens::render(zoom, *one.source, render_options);
  const Image direct = render_frame(direct_source);
  // The frame as a 1x raster, magnified the same way.
  const geolens::MipPyramid raster(render_frame(one));
  render_options.source_scale = 1;
  const Image blown_up = geolens::render(zoom, raster, render_options);

  const double close = mean_absolute_difference(magnified, direct);
  EXPECT_LT(close, 4) << "grey levels";  // measured 2.3: the levels at zoom 2 and 4 blended
  EXPECT_GT(mean_absolute_difference(blown_up, direct), 2 * close);                  // measured 8.6
  EXPECT_GT(image_gradient_energy(magnified), 3 * image_gradient_energy(blown_up));  // 6x
}

TEST_F(SvgSourceTest, RendersTheSameOnSeveralThreads) {
  // Text too: its tiles are drawn by several librsvg handles at once, one per rendering thread.
  std::string svg = R"(<svg xmlns="http://www.w3.org/2000/svg" width="200" height="150">)";
  for (int i = 0; i < 12; ++i)
    svg += "<text x=\"5\" y=\"" + std::to_string(12 + 12 * i) + "\" font-size=\"9\">line " +
           std::to_string(i) + ": focus and context</text>";
  svg += R"(<rect x="120" y="20" width="60" height="40" fill="black"/></svg>)";
  write_text(path("a.svg"), svg);
  const SourceFile one = geolens::open_svg(path("a.svg"));
  const SourceFile four = geolens::open_svg(path("a.svg"));
  // A uniform zoom 8 onto 1600 x 1200: the 2 x 2 tiles of level 0, drawn by the rendering
  // threads.
  WarpMesh zoom = geolens::identity_warp(200, 150);
  zoom.screen *= 8;
  zoom.screen_width = 1600;
  zoom.screen_height = 1200;
  geolens::RenderOptions options;
  options.width = 1600;
  options.height = 1200;
  options.source_scale = one.scale;
  options.threads = 1;
  const Image a = geolens::render(zoom, *one.source, options);
  options.threads = 4;
  const Image b = geolens::render(zoom, *four.source, options);
  EXPECT_TRUE(a.pixels == b.pixels);
  const auto counters = four.counters();
  ASSERT_EQ(counters.size(), 3u);
  EXPECT_EQ(counters[0].first, "tiles");
  EXPECT_GE(counters[0].second, 4);  // level 0: 1600 x 1200 texels in tiles of 1024
  EXPECT_EQ(counters[2].first, "svg_handles");
  EXPECT_GE(counters[2].second, 1);
  EXPECT_LE(counters[2].second, 4);
}

TEST_F(SvgSourceTest, MalformedSvgIsRefusedNamingTheFile) {
  write_text(path("bad.svg"),
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\">\n"
             "<rect x=\"1\" <oops/>\n</svg>\n");
  try {
    geolens::open_source(path("bad.svg"));
    FAIL() << "not refused";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("open_svg"), std::string::npos) << what;
    EXPECT_NE(what.find(path("bad.svg")), std::string::npos) << what;
    EXPECT_NE(what.find("librsvg"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  EXPECT_THROW(geolens::open_svg(path("missing.svg")), InvalidInput);
  // No width, height or viewBox: a size is needed.
  write_text(path("sizeless.svg"),
             "<svg xmlns=\"http://www.w3.org/2000/svg\"><rect width=\"5\" "
             "height=\"5\"/></svg>");
  EXPECT_THROW(geolens::open_svg(path("sizeless.svg")), InvalidInput);
  SourceFileOptions options;
  options.width = 40;
  options.height = 30;
  EXPECT_EQ(geolens::open_svg(path("sizeless.svg"), options).frame_width, 40);
}

}  // namespace
