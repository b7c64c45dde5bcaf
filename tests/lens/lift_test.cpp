#include "lens/lift.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geolens/core/errors.h"
#include "geolens/geometry/grid.h"

namespace geolens {
namespace {

// Two overlapping circle lenses of equal height: at the midpoint between their centres the
// heights are equal. A max would have a kink there (falling on one side, rising on the other);
// the combined lift's slopes from the left and from the right agree.
TEST(Lift, OverlappingLensesCombineWithoutACrease) {
  const std::vector<Lens> lenses = {Lens{Region::circle({400, 500}, 150)},
                                    Lens{Region::circle({600, 500}, 150)}};
  const std::vector<double> heights = {100, 100};
  auto z = [&](double x) { return lift_height(lenses, heights, {x, 500}); };
  // Difference of the one-sided slopes at the midpoint: 2 slope for a max whatever the step;
  // for a lift with a continuous gradient, proportional to the step.
  auto kink = [&](double step) {
    return std::abs((z(500 + step) - z(500)) / step - (z(500) - z(500 - step)) / step);
  };
  const double slope = std::abs(lens_height(lenses[0], 100, {500.5, 500}) -
                                lens_height(lenses[0], 100, {499.5, 500}));
  ASSERT_GT(slope, 0.1);  // each lens alone is steep there
  EXPECT_LT(kink(0.25), 0.1 * 2 * slope);
  EXPECT_LT(kink(0.0625), 0.3 * kink(0.25));
  // Where only one lens lifts, the lift is that lens's height.
  EXPECT_DOUBLE_EQ(z(300), lens_height(lenses[0], 100, {300, 500}));
  EXPECT_DOUBLE_EQ(z(720), lens_height(lenses[1], 100, {720, 500}));
  // The grid lift agrees with lift_height, and so does the field's log zoom, in units of size.
  const Grid grid = make_grid(1000, 1000, 41);
  const Lifted lifted = lift(grid.V, lenses, heights);
  for (Eigen::Index i = 0; i < grid.V.rows(); ++i) {
    const double h = lift_height(lenses, heights, grid.V.row(i).transpose());
    EXPECT_NEAR(lifted.V(i, 2), h, 1e-9 * (1 + h));
    EXPECT_NEAR(lifted.log_zoom(i), h / 150, 1e-9 * (1 + h));
  }
  EXPECT_THROW(lift_height(lenses, {100}, {0, 0}), InvalidInput);
}

}  // namespace
}  // namespace geolens
