// The numerical sweep over every model and every kind of region (issue 29, item 7): seeded setups
// of 1 to 3 lenses on a 512 x 384 image, each a random star-shaped polygon of 3 to 400 vertices
// (jagged: corners down to a hundredth of a degree; simplified as the CLI simplifies them), an
// ellipse mask or a circle, at zooms 1 to 8, solved by the focus, lift and field models. None
// throws, none gives a coordinate that is not finite, each takes under 5 s; the focus model
// flips nothing and measures the zoom it reports (within 1 %); the lift and field models flip a few
// triangles in about one setup in ten (docs/cli.md says so).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/io/image.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens_spec.h"
#include "geolens/measure/distortion.h"
#include "geometry/polygon.h"

namespace geolens {
namespace {

constexpr int kWidth = 512, kHeight = 384, kSetups = 100;
// A time means something in an optimized build only (scripts/sanitize.sh builds at -O1 with
// Eigen's assertions, where a setup of 0.4 s took 36 s): there each setup gets 5 s of CPU time,
// on one thread. CPU time, not wall time: on a machine whose cores other jobs share (a CI run
// beside builds, load average 10 on 2 cores) setups of 2-3 s took 5-7 s of wall time.
#ifdef NDEBUG
constexpr double kSetupSeconds = 5;
#else
constexpr double kSetupSeconds = std::numeric_limits<double>::infinity();
#endif

// One setup's lenses, all of one kind, drawn from `random`.
std::vector<Lens> random_lenses(std::mt19937& random) {
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Lens> lenses;
  const int count = 1 + int(unit(random) * 3);
  const double kind = unit(random);
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector2d c(40 + unit(random) * (kWidth - 80), 40 + unit(random) * (kHeight - 80));
    const double r = 8 + std::pow(unit(random), 2) * 120, zoom = 1 + unit(random) * 7;
    if (kind < 0.6) {
      const int n = 3 + int(std::pow(unit(random), 3) * 400);
      std::vector<double> angles(size_t(n), 0.0);
      for (double& a : angles) a = unit(random) * 2 * std::numbers::pi;
      std::sort(angles.begin(), angles.end());
      std::vector<Eigen::Vector2d> v;
      for (const double a : angles) {
        const Eigen::Vector2d p =
            c + r * (0.3 + 0.7 * unit(random)) * Eigen::Vector2d(std::cos(a), std::sin(a));
        v.push_back(
            p.cwiseMax(Eigen::Vector2d(1, 1)).cwiseMin(Eigen::Vector2d(kWidth - 1, kHeight - 1)));
      }
      v = simplify_loop(v, kPolygonTolerance);
      try {
        validate_polygon(v, "sweep");  // a lens file the CLI would refuse is not a setup
        lenses.push_back(Lens{Region::polygon(v), zoom});
      } catch (const InvalidInput&) {
      }
    } else if (kind < 0.8) {
      Image mask(kWidth, kHeight, 1, 0);
      const double ax = r, ay = r * (0.3 + 0.7 * unit(random));
      for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
          const double dx = (x - c.x()) / ax, dy = (y - c.y()) / ay;
          if (dx * dx + dy * dy < 1) mask.at(x, y)[0] = 255;
        }
      for (Region& blob : Region::from_mask(mask)) lenses.push_back(Lens{std::move(blob), zoom});
    } else {
      lenses.push_back(Lens{Region::circle(c, r), zoom});
    }
  }
  return lenses;
}

TEST(ModelSweep, EveryModelSolvesEveryKindOfRegion) {
  const LensModel models[] = {LensModel::kFocus, LensModel::kLift, LensModel::kField};
  int flipped_setups[3] = {0, 0, 0}, setups = 0;
  double slowest = 0;  // CPU seconds of the slowest setup
  std::mt19937 random(1);
  for (int s = 0; s < kSetups; ++s) {
    const std::vector<Lens> lenses = random_lenses(random);
    if (lenses.empty()) continue;
    ++setups;
    for (int m = 0; m < 3; ++m) {
      LensOptions options;
      options.mesh = 60;
      options.model = models[m];
      options.flatten.threads = 1;  // so the process's CPU time is the solve's time
      SCOPED_TRACE("setup " + std::to_string(s) + ", the " + to_string(models[m]) + " model");
      const std::clock_t start = std::clock();
      LensResult r;
      ASSERT_NO_THROW(r = GeometricLens(kWidth, kHeight, options).solve(lenses));
      const double seconds = double(std::clock() - start) / CLOCKS_PER_SEC;
      EXPECT_LT(seconds, kSetupSeconds);
      slowest = std::max(slowest, seconds);
      EXPECT_TRUE(r.warp.screen.allFinite());
      if (models[m] == LensModel::kFocus)  // the zoom reported is the zoom measured
        for (size_t k = 0; k < lenses.size(); ++k)
          EXPECT_NEAR(r.zoom_measured[k], r.zoom_fits[k], 0.01 * r.zoom_fits[k]) << "lens " << k;
      flipped_setups[m] += summarize(measure_triangles(r.warp)).flipped > 0;
    }
  }
  EXPECT_GT(setups, 90);
  EXPECT_EQ(flipped_setups[0], 0);
  for (int m : {1, 2}) EXPECT_LE(flipped_setups[m], setups / 6) << to_string(models[m]);
  ::testing::Test::RecordProperty("lift_flipped_setups", flipped_setups[1]);
  std::cout << "slowest setup: " << slowest << " s of CPU time\n";
  ::testing::Test::RecordProperty("field_flipped_setups", flipped_setups[2]);
}

// Setups of other seeds where the focus model once flipped a triangle, each the product of the
// mesh that follows the regions: seed 2's setup 173 (two polygons magnified as one, whose curves
// crossed within a millionth of a cell of a vertex: degenerate triangles) and 290 (a 13 px
// polygon at zoom 5: three points of its outline 1.5e-10 px off a line at a corner).
TEST(ModelSweep, FocusModelSetupsThatOnceFlipped) {
  std::mt19937 random(2);
  for (int s = 0; s <= 290; ++s) {
    const std::vector<Lens> lenses = random_lenses(random);
    if (s != 173 && s != 290) continue;
    SCOPED_TRACE("seed 2, setup " + std::to_string(s));
    LensOptions options;
    options.mesh = 60;
    const LensResult r = GeometricLens(kWidth, kHeight, options).solve(lenses);
    EXPECT_EQ(summarize(measure_triangles(r.warp)).flipped, 0);
    for (size_t k = 0; k < lenses.size(); ++k)
      EXPECT_NEAR(r.zoom_measured[k], r.zoom_fits[k], 0.01 * r.zoom_fits[k]) << "lens " << k;
  }
}

}  // namespace
}  // namespace geolens
