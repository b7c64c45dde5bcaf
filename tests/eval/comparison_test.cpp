// The comparison of the geometric lens with the classic lenses, called as a library: the methods
// and their order, every classic lens matched to the geometric lens's measured zoom by the same
// measure, the flat tops' uniform focus, the targets per lens model, the report's JSON (one entry
// per method, the lens object of run_stats_json) and Markdown, the pictures' sizes, and the
// footprint sweep's text.

#include "geolens/eval/comparison.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/eval/run_stats.h"
#include "geolens/lens/classic_lens.h"
#include "lens/focus_lens.h"
#include "support/lens_options.h"

namespace geolens {
namespace {

constexpr int kSide = 256;

LensOptions small_mesh(LensOptions options = {}) {
  options.mesh = 60;
  return options;
}

// One focus lens of radius 25 at zoom 2 (footprint 100 px) in the middle of a 256 x 256 source,
// compared once for every test that reads it.
const Comparison& circle_comparison() {
  static const Comparison c =
      compare_lenses(kSide, kSide, {Lens{Region::circle({128, 128}, 25), 2.0}}, small_mesh(), 80);
  return c;
}

// A kSide x kSide colour pattern.
Image pattern() {
  Image image(kSide, kSide, 3);
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      uint8_t* p = image.at(x, y);
      p[0] = uint8_t(x);
      p[1] = uint8_t(y);
      p[2] = uint8_t(((x / 8 + y / 8) % 2) * 200);
    }
  return image;
}

std::set<std::string> keys(const nlohmann::json& object) {
  std::set<std::string> names;
  for (const auto& item : object.items()) names.insert(item.key());
  return names;
}

TEST(Comparison, MethodsAreTheGeometricLensThenEveryClassicLens) {
  const Comparison& c = circle_comparison();
  std::vector<std::string> expected = {"geometric"};
  for (ClassicLens kind : kClassicLenses) expected.push_back(to_string(kind));
  std::vector<std::string> names;
  for (const ComparedMethod& m : c.methods) names.push_back(m.name);
  EXPECT_EQ(names, expected);
  EXPECT_EQ(comparison_methods(c.lenses, small_mesh()), expected);
  for (const ComparedMethod& m : c.methods) {
    SCOPED_TRACE(m.name);
    EXPECT_EQ(m.warp.screen_width, kSide);
    EXPECT_EQ(m.warp.screen_height, kSide);
    EXPECT_EQ(m.measures.conformal.size(), m.warp.F.rows());
    EXPECT_EQ(m.zoom_measured.size(), 1u);
    EXPECT_EQ(m.foci.size(), 1u);
    EXPECT_EQ(m.regions.overall.flipped, 0);
  }
}

// Every classic lens is matched (within match_classic_lens's 0.5 %) to the zoom the geometric
// lens measured, and every zoom is the same measure: magnification_at the centre over
// zoom_measure_radius, the radius GeometricLens itself measures over.
TEST(Comparison, EveryMethodIsMatchedToTheGeometricZoomBySameMeasure) {
  const Comparison& c = circle_comparison();
  const double geometric = c.geometric.zoom_measured[0];
  EXPECT_NEAR(geometric, 2, 0.05);
  EXPECT_EQ(c.methods[0].zoom_measured, c.geometric.zoom_measured);
  EXPECT_DOUBLE_EQ(c.targets[0].zoom, geometric);
  const double radius =
      zoom_measure_radius(c.lenses[0].region.size(), c.geometric.box.sizes().maxCoeff(), 60);
  for (const ComparedMethod& m : c.methods) {
    SCOPED_TRACE(m.name);
    EXPECT_NEAR(m.zoom_measured[0] / geometric, 1, 0.005 + 1e-9);
    EXPECT_DOUBLE_EQ(m.zoom_measured[0],
                     magnification_at(m.warp, m.measures, c.lenses[0].region.peak(), radius));
  }
}

// zoom_in, bifocal, the flat tops and the power ring are uniform on the focus by construction;
// the zoom-in distorts nothing and hides the ring under its inset, pi R^2 (1 - 1 / z^2).
TEST(Comparison, FlatTopsHaveAUniformUndistortedFocus) {
  const Comparison& c = circle_comparison();
  for (size_t i = 1; i < c.methods.size(); ++i) {
    const ComparedMethod& m = c.methods[i];
    if (m.name == "fisheye" || m.name == "fisheye_smooth") continue;
    SCOPED_TRACE(m.name);
    EXPECT_NEAR(m.regions.focus_uniformity, 1, 1e-9);
    EXPECT_LT(m.regions.focus.conformal_max, 1e-9);
  }
  const ComparedMethod& zoom_in = c.methods[1];
  ASSERT_EQ(zoom_in.name, "zoom_in");
  EXPECT_LT(zoom_in.regions.overall.conformal_max, 1e-9);
  const double R = c.targets[0].radius, z = c.targets[0].zoom;
  const double hidden = std::numbers::pi * R * R * (1 - 1 / (z * z)) / (kSide * kSide) * 100;
  EXPECT_NEAR(zoom_in.regions.occluded_percent, hidden, 0.03 * hidden);
  // The geometric focus lens: a uniform, undistorted focus, nothing hidden.
  EXPECT_NEAR(c.methods[0].foci[0].uniformity, 1, 0.02);
  EXPECT_NEAR(c.methods[0].regions.occluded_percent, 0, 1e-9);
}

TEST(Comparison, TargetsFollowTheLensModel) {
  const Lens lens{Region::circle({100, 90}, 20), 3.0};
  const CircleLens focus = classic_target(lens, LensOptions{}, 2.5);
  EXPECT_EQ(focus.center, Eigen::Vector2d(100, 90));
  EXPECT_DOUBLE_EQ(focus.radius, footprint_ratio(lens) * 20);
  EXPECT_DOUBLE_EQ(focus.zoom, 2.5);
  EXPECT_DOUBLE_EQ(focus.focus_fraction, 2.5 / footprint_ratio(lens));
  const CircleLens lift = classic_target(lens, test::auto_model(), 2.5);
  EXPECT_DOUBLE_EQ(lift.radius, 20);
  EXPECT_DOUBLE_EQ(lift.focus_fraction, kFocusFraction);
  EXPECT_DOUBLE_EQ(classic_radius(lens, test::auto_model()), 20);
}

// The classic lenses are radial and do not compose: a polygon's are fitted to its disk, and
// overlapping disks are refused naming the caller.
TEST(Comparison, PolygonsFittedToTheirDiskAndOverlappingDisksRefused) {
  const std::vector<Lens> overlapping = {Lens{Region::circle({60, 60}, 20)},
                                         Lens{Region::circle({120, 120}, 20)}};
  try {
    comparison_methods(overlapping, LensOptions{}, "--lens");
    FAIL() << "overlapping lenses accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("--lens"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("overlap"), std::string::npos) << e.what();
  }
  EXPECT_EQ(comparison_methods(overlapping, test::auto_model()).size(), 8u);  // radius 20 each
  EXPECT_THROW(compare_lenses(kSide, kSide, overlapping, small_mesh()), InvalidInput);
  EXPECT_THROW(
      compare_lenses(kSide, kSide, {Lens{Region::circle({128, 128}, 25)}}, small_mesh(), 3),
      InvalidInput);

  const Lens square{Region::polygon({{100, 100}, {160, 100}, {160, 150}, {100, 150}}), 2.0};
  EXPECT_EQ(comparison_methods({square}, LensOptions{}).size(), 8u);
  const Comparison c = compare_lenses(kSide, kSide, {square}, small_mesh(), 80);
  ASSERT_EQ(c.methods.size(), 8u);
  EXPECT_NEAR(c.methods[0].foci[0].zoom, 2, 0.05);
  // The disk about the peak holding the region, its flat top showing the region at full zoom.
  const CircleLens& target = c.targets[0];
  EXPECT_DOUBLE_EQ(target.radius, classic_radius(square, small_mesh()));
  EXPECT_DOUBLE_EQ(target.radius, footprint_ratio(square) * square.region.reach());
  EXPECT_EQ(target.center, square.region.peak());
  EXPECT_NEAR(target.focus_fraction * target.radius / target.zoom, square.region.reach(), 1e-9);
  // The footprint drawn: the square scaled by the ratio about its peak.
  ASSERT_EQ(c.footprints[0].size(), 4u);
  const std::vector<Eigen::Vector2d> corners = *square.region.outline();
  for (size_t i = 0; i < 4; ++i)
    EXPECT_LT((c.footprints[0][i] -
               (target.center + footprint_ratio(square) * (corners[i] - target.center)))
                  .norm(),
              1e-9);
}

// A circle's footprint outline is its footprint's circle, whatever the model's disk.
TEST(Comparison, FootprintOutlineOfACircleIsTheDiskMeasured) {
  const Lens lens{Region::circle({100, 90}, 20), 2.0};
  for (const LensOptions& options : {LensOptions{}, test::auto_model()}) {
    const std::vector<Eigen::Vector2d> outline = footprint_outline(lens, options);
    ASSERT_GE(outline.size(), 64u);
    for (const Eigen::Vector2d& p : outline)
      EXPECT_NEAR((p - Eigen::Vector2d(100, 90)).norm(), classic_radius(lens, options), 1e-9);
  }
}

// The JSON parses, holds one entry per method in order, and each lens is the object
// run_stats_json writes (the same keys, but the solve's `height`, `zoom_fit` and
// `zoom_fit_reason`).
TEST(ComparisonReport, JsonHasOneEntryPerMethodAndTheLensObjectOfRunStats) {
  const Comparison& c = circle_comparison();
  const nlohmann::json j = nlohmann::json::parse(comparison_json(c));
  const nlohmann::json& methods = j.at("methods");
  ASSERT_EQ(methods.size(), c.methods.size());
  const nlohmann::json stats = nlohmann::json::parse(run_stats_json(
      c.lenses, small_mesh(), c.geometric, summarize(c.methods[0].measures), RunTimings{}));
  std::set<std::string> lens_keys = keys(stats.at("lenses")[0]);
  lens_keys.erase("height");
  lens_keys.erase("zoom_fit");
  lens_keys.erase("zoom_fit_reason");
  for (size_t i = 0; i < c.methods.size(); ++i) {
    const nlohmann::json& m = methods[i];
    SCOPED_TRACE(c.methods[i].name);
    EXPECT_EQ(m.at("name"), c.methods[i].name);
    EXPECT_EQ(m.at("zoom_center").get<double>(), c.methods[i].zoom_measured[0]);
    EXPECT_EQ(m.at("distortion").size(), 4u);
    ASSERT_EQ(m.at("lenses").size(), 1u);
    const nlohmann::json& lens = m.at("lenses")[0];
    EXPECT_EQ(keys(lens), lens_keys);
    EXPECT_EQ(lens.at("zoom_measured").get<double>(), c.methods[i].zoom_measured[0]);
    EXPECT_EQ(lens.at("focus").at("uniformity").get<double>(), c.methods[i].foci[0].uniformity);
  }
  EXPECT_EQ(methods[0].at("lenses")[0], [&] {
    nlohmann::json lens = stats.at("lenses")[0];
    lens.erase("height");
    lens.erase("zoom_fit");
    lens.erase("zoom_fit_reason");
    return lens;
  }());
}

TEST(ComparisonReport, MarkdownHasARowPerMethod) {
  const Comparison& c = circle_comparison();
  const std::string md = comparison_markdown(c, "pattern.png");
  EXPECT_EQ(md.rfind("# geolens compare: pattern.png\n", 0), 0u);
  for (const ComparedMethod& m : c.methods)
    EXPECT_NE(md.find("| " + m.name + " | 1 |"), std::string::npos) << m.name;  // per lens
  EXPECT_NE(md.find("Eq. 7 energy"), std::string::npos);
  EXPECT_GT(c.eq7_energy, 0);
}

TEST(ComparisonImages, OutputsHeatmapsAndPanelHaveTheDocumentedSizes) {
  const Comparison& c = circle_comparison();
  const SourceFile pyramid = image_source(pattern());
  const double heat_max = comparison_heat_max(c);
  double largest = 0;
  for (const ComparedMethod& m : c.methods)
    largest = std::max(largest, m.regions.overall.conformal_max);
  EXPECT_EQ(heat_max, largest);
  const ComparedMethod& m = c.methods[0];
  const Image output = comparison_output(c, m, pyramid);
  EXPECT_EQ(output.width, kSide);
  EXPECT_EQ(output.height, kSide);
  EXPECT_EQ(output.channels, 3);
  const Image heat = comparison_heatmap(m, output, heat_max);
  EXPECT_EQ(heat.width, kSide);
  EXPECT_GT(heat.height, kSide);  // the scale below
  for (int tile : {64, 176}) {
    SCOPED_TRACE(tile);
    const Image panel = comparison_panel(c, pyramid, heat_max, tile);
    const int line = tile >= 176 ? 22 : 11, rows = 3;  // the input and 8 methods, 4 per row
    EXPECT_EQ(panel.width, 4 * (tile + 6) + 6);
    EXPECT_GT(panel.height, rows * (4 * line + 2 * tile + 24) + 6);
    EXPECT_EQ(panel.channels, 3);
  }
  EXPECT_THROW(comparison_panel(c, pyramid, heat_max, 63), InvalidInput);
  EXPECT_THROW(comparison_panel(c, pyramid, heat_max, 1025), InvalidInput);
}

TEST(Comparison, ZoomOneIsTheIdentityForEveryMethod) {
  const Comparison c =
      compare_lenses(128, 128, {Lens{Region::circle({64, 64}, 20), 1.0}}, small_mesh(), 40);
  ASSERT_EQ(c.methods.size(), 8u);
  for (const ComparedMethod& m : c.methods) {
    SCOPED_TRACE(m.name);
    EXPECT_NEAR(m.zoom_measured[0], 1, 1e-9);
    EXPECT_LT(m.regions.overall.conformal_max, 1e-9);
    EXPECT_NEAR(m.regions.occluded_percent, 0, 1e-9);
  }
}

// The sweep's text: a JSON point per method and ratio, a Markdown row per ratio.
TEST(ComparisonReport, SweepTextHasEveryPoint) {
  EXPECT_EQ(sweep_ratios(2), (std::vector<double>{3, 4, 6, 8}));
  EXPECT_EQ(sweep_ratios(1), (std::vector<double>{1.5, 2, 3, 4}));
  LensOptions options;
  options.mesh = 40;
  const Lens lens{Region::circle({64, 64}, 8), 2.0};
  const Sweep sweep = footprint_sweep(128, 128, lens, options, {3, 6}, 40);
  const nlohmann::json points = nlohmann::json::parse(sweep_json(sweep)).at("points");
  ASSERT_EQ(points.size(), sweep.points.size());
  EXPECT_EQ(points.size(), 2 * (1 + kClassicLenses.size()));
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(points[i].at("method"), sweep.points[i].method);
    EXPECT_EQ(points[i].at("ratio").get<double>(), sweep.points[i].ratio);
    EXPECT_GT(points[i].at("bound").get<double>(), 0);
  }
  const std::string md = sweep_markdown(sweep, "grid.png");
  EXPECT_EQ(md.rfind("# geolens compare --sweep: grid.png\n", 0), 0u);
  EXPECT_NE(md.find("\n| 3.00 |"), std::string::npos);
  EXPECT_NE(md.find("\n| 6.00 |"), std::string::npos);
}

}  // namespace
}  // namespace geolens
