#include "geolens/render/annotate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geolens/core/errors.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens {
namespace {

// The outline is a ring about 3 pixels wide on the region's boundary, nothing elsewhere.
TEST(Annotate, OutlineFollowsTheBoundaryAtTheGivenScale) {
  Image image(200, 100, 3, 0);
  // Source 400 x 200 shown at half size: a circle of radius 60 at (200, 100) is one of 30 at
  // (100, 50) on the image.
  outline_regions(image, {Region::circle({200, 100}, 60)}, Eigen::Vector2d::Zero(), 0.5, 0.5);
  int marked = 0;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 200; ++x) {
      if (image.at(x, y)[0] == 0) continue;
      ++marked;
      EXPECT_NEAR(std::hypot(x + 0.5 - 100, y + 0.5 - 50), 30, 2.0) << x << ", " << y;
      EXPECT_EQ(image.at(x, y)[1], 30);  // red
    }
  EXPECT_GT(marked, int(2 * M_PI * 30 * 2));  // about 2 pixels on either side of the rim
  Image grey(10, 10, 1, 0);
  outline_regions(grey, {Region::circle({5, 5}, 3)}, Eigen::Vector2d::Zero(), 1, 1);
  EXPECT_EQ(grey.at(2, 5)[0], 80);  // grey on grey images
}

TEST(Annotate, SideBySidePasteAndRgb) {
  const Image joined = side_by_side(Image(3, 2, 3, 10), Image(4, 5, 3, 20), 2);
  EXPECT_EQ(joined.width, 9);
  EXPECT_EQ(joined.height, 5);
  EXPECT_EQ(joined.at(0, 0)[0], 10);
  EXPECT_EQ(joined.at(4, 0)[0], 255);  // the gap
  EXPECT_EQ(joined.at(0, 3)[0], 255);  // below the shorter one
  EXPECT_EQ(joined.at(8, 4)[0], 20);
  EXPECT_THROW(side_by_side(Image(2, 2, 1), Image(2, 2, 3)), InvalidInput);
  Image target(4, 4, 3);
  EXPECT_THROW(paste(target, Image(3, 3, 3), 2, 0), InvalidInput);
  const Image rgb = to_rgb(Image(2, 2, 1, 77));
  EXPECT_EQ(rgb.channels, 3);
  EXPECT_EQ(rgb.at(1, 1)[2], 77);
}

TEST(Annotate, IdentityWarpCoversTheSource) {
  const WarpMesh w = identity_warp(30, 20);
  EXPECT_EQ(w.F.rows(), 2);
  EXPECT_EQ(w.source, w.screen);
  EXPECT_EQ(w.source.colwise().maxCoeff(), Eigen::RowVector2d(30, 20));
  EXPECT_EQ(w.screen_width, 30);
  EXPECT_THROW(identity_warp(0, 5), InvalidInput);
}

}  // namespace
}  // namespace geolens
