#include "geolens/geometry/roi.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "geolens/core/errors.h"
#include "geolens/io/image.h"
#include "support/polygon_reference.h"

namespace geolens {
namespace {

using Points = std::vector<Eigen::Vector2d>;
constexpr double kPi = std::numbers::pi;

Points regular_polygon(const Eigen::Vector2d& centre, double radius, int n) {
  Points p;
  for (int k = 0; k < n; ++k) {
    const double a = 0.05 + 2 * kPi * k / n;
    p.push_back(centre + radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return p;
}

Points l_shape(double scale = 1) {
  Points p{{0, 0}, {200, 0}, {200, 60}, {60, 60}, {60, 200}, {0, 200}};
  for (Eigen::Vector2d& v : p) v = scale * v + Eigen::Vector2d(10, 10);
  return p;
}

/// A five-pointed star of outer radius R around `centre`, turned by `angle`; its inner vertices
/// at 0.382 R (the regular star's).
Points star(const Eigen::Vector2d& centre, double R, double angle) {
  Points p;
  for (int k = 0; k < 10; ++k) {
    const double a = angle + k * kPi / 5 - kPi / 2, r = k % 2 ? 0.382 * R : R;
    p.push_back(centre + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return p;
}

/// How fast the fields vary between neighbouring samples `step` apart over the region's box.
struct Variation {
  /// Largest |depth(p) - depth(q)| * thickness / step, thickness the smaller of the two. Since a
  /// and b are 1-Lipschitz, b / (a + b) changes by at most step / (a + b): this is about 1 for a
  /// continuous depth, yet allows the jump at a convex corner tip where thickness -> 0.
  double depth = 0;
  /// Largest |thickness(p) - thickness(q)| / step with p and q inside: at most 2 for a + b.
  double thickness = 0;
};

Variation variation(const Region& region, double step) {
  const Eigen::AlignedBox2d box = region.bounds();
  Variation v;
  for (double y = box.min().y() - 2; y <= box.max().y() + 2; y += step) {
    for (double x = box.min().x() - 2; x <= box.max().x() + 2; x += step) {
      const Eigen::Vector2d p(x, y);
      for (const Eigen::Vector2d& q :
           {Eigen::Vector2d(x + step, y), Eigen::Vector2d(x, y + step)}) {
        const double dp = region.depth(p), dq = region.depth(q);
        const double tp = region.thickness(p), tq = region.thickness(q);
        v.depth = std::max(v.depth, std::abs(dp - dq) * std::min(tp, tq) / step);
        if (dp > 0 && dq > 0) v.thickness = std::max(v.thickness, std::abs(tp - tq) / step);
      }
    }
  }
  return v;
}

TEST(PolygonRegion, ManySidedRegularPolygonBehavesLikeACircle) {
  const Eigen::Vector2d c(150, 120);
  const double r = 100;
  const Points poly = regular_polygon(c, r, 64);
  const Region region = Region::polygon(poly);
  EXPECT_EQ(region.kind(), "polygon");
  EXPECT_EQ(region.anchors(), poly);
  EXPECT_FALSE(region.circle());
  EXPECT_LE((region.peak() - c).norm(), 1.5);
  EXPECT_NEAR(region.size(), r, 1.5);
  for (int k = 0; k < 16; ++k) {
    const Eigen::Vector2d dir(std::cos(0.4 * k), std::sin(0.4 * k));
    for (double d = 0; d < 0.99 * r; d += 3.7) {
      EXPECT_NEAR(region.depth(c + d * dir), 1 - d / r, 0.02) << k << " " << d;
      EXPECT_NEAR(region.thickness(c + d * dir), r, 2.0) << k << " " << d;
    }
    EXPECT_EQ(region.depth(c + 1.01 * r * dir), 0);
  }
}

TEST(PolygonRegion, DepthIsZeroExactlyOnTheBoundaryAndOutside) {
  const Points poly = l_shape();
  const Region region = Region::polygon(poly);
  for (size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d a = poly[i], b = poly[(i + 1) % poly.size()];
    for (int k = 0; k <= 64; ++k) EXPECT_EQ(region.depth(a + (b - a) * k / 64.0), 0) << i << k;
  }
  for (double y = -5; y < 220; y += 1.3) {
    for (double x = -5; x < 220; x += 1.3) {
      if (!testing::brute_inside(poly, {x, y})) {
        EXPECT_EQ(region.depth({x, y}), 0) << x << " " << y;
      }
    }
  }
  EXPECT_EQ(region.depth({-1e9, 5}), 0);
  EXPECT_EQ(region.thickness({-1e9, 5}), 0);
}

TEST(PolygonRegion, LShapeDepthIsOneOnTheArmCentreLinesAndPeaksThere) {
  const Region region = Region::polygon(l_shape());
  // Arm centre lines: y = 40 for the horizontal arm, x = 40 for the vertical one (offset 10).
  for (double s = 80; s <= 170; s += 1.7) {
    EXPECT_GE(region.depth({s, 40}), 0.97) << s;
    EXPECT_GE(region.depth({40, s}), 0.97) << s;
    EXPECT_NEAR(region.thickness({s, 40}), 30, 1.0) << s;
    // Across the arm the depth rises from the boundary to the centre line and falls again,
    // 1 - |t - 30| / 30 for the depth b / (a + b) of a strip.
    double previous = 0;
    for (double t = 0.25; t < 60; t += 0.25) {
      const double depth = region.depth({s, 10 + t});
      EXPECT_NEAR(depth, 1 - std::abs(t - 30) / 30, 0.03) << s << " " << t;
      if (t <= 29) {
        EXPECT_GE(depth, previous - 1e-9) << s << " " << t;
      } else if (t >= 31) {
        EXPECT_LE(depth, previous + 1e-9) << s << " " << t;
      }
      previous = depth;
    }
  }
  // The largest inscribed circle touches both outer sides and the reflex corner.
  const double j = 60 * std::sqrt(2.0) / (1 + std::sqrt(2.0));
  EXPECT_LE((region.peak() - Eigen::Vector2d(10 + j, 10 + j)).norm(), 1.5);
  EXPECT_NEAR(region.size(), j, 1.0);
  EXPECT_NEAR(region.depth(region.peak()), 1.0, 1e-12);
  EXPECT_NEAR(region.thickness(region.peak()), region.size(), 1e-12);
}

TEST(PolygonRegion, LShapeFieldsAreContinuous) {
  const Variation v = variation(Region::polygon(l_shape()), 0.5);
  EXPECT_LE(v.depth, 1.5);
  EXPECT_LE(v.thickness, 2.5);
}

class StarRegion : public ::testing::TestWithParam<double> {};

TEST_P(StarRegion, DepthIsOneOnTheSpokesZeroOnTheBoundaryAndContinuous) {
  const Eigen::Vector2d c(200, 180);
  const double R = 150;
  const Points poly = star(c, R, GetParam());
  const Region region = Region::polygon(poly);
  EXPECT_LE((region.peak() - c).norm(), 1.5);
  EXPECT_TRUE(testing::brute_inside(poly, region.peak()));
  for (size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d a = poly[i], b = poly[(i + 1) % poly.size()];
    for (int k = 0; k <= 64; ++k) EXPECT_NEAR(region.depth(a + (b - a) * k / 64.0), 0, 1e-12);
  }
  for (double y = c.y() - R - 5; y < c.y() + R + 5; y += 2.9) {
    for (double x = c.x() - R - 5; x < c.x() + R + 5; x += 2.9) {
      if (!testing::brute_inside(poly, {x, y})) {
        EXPECT_EQ(region.depth({x, y}), 0) << x << " " << y;
      }
    }
  }
  for (size_t tip = 0; tip < poly.size(); tip += 2) {
    const Eigen::Vector2d along = (poly[tip] - c) / R, across(-along.y(), along.x());
    for (double s = 0; s <= 0.85 * R; s += 3.1) {
      const Eigen::Vector2d p = c + s * along;
      // b / (a + b) with the raster's axis within a pixel of the spoke.
      const double b = testing::brute_boundary_distance(poly, p);
      EXPECT_GE(region.depth(p), b / (b + 1)) << tip << " " << s;
      // Maximal on the spoke, away from the centre where the spokes meet: it falls off to either
      // side.
      if (s >= 0.2 * R) {
        EXPECT_LT(region.depth(p + 0.3 * b * across), region.depth(p)) << tip << " " << s;
        EXPECT_LT(region.depth(p - 0.3 * b * across), region.depth(p)) << tip << " " << s;
      }
      // Thickness along a spoke is the half-width of the arm there.
      EXPECT_NEAR(region.thickness(p), testing::brute_boundary_distance(poly, p), 1.0)
          << tip << " " << s;
    }
  }
  const Variation v = variation(region, 0.5);
  EXPECT_LE(v.depth, 1.5);
  EXPECT_LE(v.thickness, 2.5);
}

INSTANTIATE_TEST_SUITE_P(Turned, StarRegion, ::testing::Values(0.0, 0.21, 0.5, 1.0));

TEST(PolygonRegion, LargePolygonOnACoarseRasterMatchesASmallOne) {
  // 25 x the L: 5000 pixels across, so its raster has ~5 pixels per cell. Away from the convex
  // corners, where each raster stops the axis branch a few of its own cells from the tip.
  const Region small = Region::polygon(l_shape());
  const Region large = Region::polygon(l_shape(25));
  const Eigen::Vector2d shift(10, 10);
  for (double y = 0; y < 200; y += 3.3) {
    for (double x = 0; x < 200; x += 3.3) {
      const Eigen::Vector2d p(x, y);
      bool near_corner = false;
      for (const Eigen::Vector2d& v : l_shape()) near_corner |= (p + shift - v).norm() < 12;
      if (near_corner) continue;
      // The small L's axis is within a pixel (one of its cells) of the exact one.
      const double expected = small.depth(p + shift);
      EXPECT_NEAR(large.depth(25 * p + shift), expected, 1.0 / small.thickness(p + shift))
          << x << " " << y;
      if (expected > 0) {
        EXPECT_NEAR(large.thickness(25 * p + shift) / 25, small.thickness(p + shift), 0.5)
            << x << " " << y;
      }
    }
  }
  EXPECT_NEAR(large.size() / 25, small.size(), 0.5);
}

TEST(PolygonRegion, TinyPolygonIsResolvedBelowAPixel) {
  const Eigen::Vector2d c(20, 20);
  const Region region = Region::polygon(regular_polygon(c, 4, 32));
  EXPECT_LE((region.peak() - c).norm(), 0.3);
  EXPECT_NEAR(region.size(), 4, 0.2);
  EXPECT_NEAR(region.depth(c + Eigen::Vector2d(2, 0)), 0.5, 0.05);
}

TEST(PolygonRegion, RejectsInvalidPolygons) {
  const std::vector<Points> bad = {
      {{0, 0}, {10, 0}},                               // too few
      {{0, 0}, {10, 0}, {10, std::nan("")}},           // not finite
      {{0, 0}, {10, 0}, {20, 0}},                      // no area
      {{0, 0}, {10, 10}, {10, 0}, {0, 10}},            // bow tie
      {{0, 0}, {10, 0}, {10, 10}, {10, 10}, {0, 10}},  // repeated vertex
      {{0, 0}, {1000, 0}, {1000, 1e-3}, {0, 1e-3}},    // thinner than its raster
  };
  for (const Points& poly : bad) {
    try {
      Region::polygon(poly);
      ADD_FAILURE() << "accepted a polygon with " << poly.size() << " vertices";
    } catch (const InvalidInput& e) {
      EXPECT_EQ(std::string(e.what()).rfind("Region::polygon: ", 0), 0u) << e.what();
    }
  }
}

Image disc_mask(int width, int height,
                const std::vector<std::pair<Eigen::Vector2d, double>>& discs) {
  Image mask(width, height, 1, 0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (const auto& [c, r] : discs) {
        if ((Eigen::Vector2d(x + 0.5, y + 0.5) - c).norm() < r) *mask.at(x, y) = 255;
      }
    }
  }
  return mask;
}

TEST(MaskRegion, EachBlobIsARegionWithItsOwnBoundsAndDepth) {
  const Eigen::Vector2d c1(150, 40), c2(60, 100);
  const Image mask = disc_mask(200, 150, {{c1, 30}, {c2, 20}});
  const std::vector<Region> regions = Region::from_mask(mask);
  ASSERT_EQ(regions.size(), 2u);
  // Raster order of the first pixel: the higher disc first.
  const Eigen::Vector2d centres[] = {c1, c2};
  const double radii[] = {30, 20};
  for (int k = 0; k < 2; ++k) {
    const Region& r = regions[size_t(k)];
    EXPECT_EQ(r.kind(), "mask");
    EXPECT_TRUE(r.anchors().empty());
    EXPECT_FALSE(r.circle());
    const Eigen::Vector2d c = centres[k];
    const double radius = radii[k];
    // Every pixel whose centre is inside the disc, as pixel squares.
    EXPECT_TRUE(
        r.bounds().isApprox(Eigen::AlignedBox2d(c.array() - radius, c.array() + radius), 1e-12))
        << r.bounds().min().transpose() << " " << r.bounds().max().transpose();
    // The peak is a pixel centre, the discs' centres pixel corners.
    EXPECT_LE((r.peak() - c).norm(), 1.0);
    EXPECT_NEAR(r.size(), radius, 1.5);
    for (double d = 0; d < radius - 1; d += 1.3) {
      const Eigen::Vector2d p = c + d * Eigen::Vector2d(0.8, -0.6);
      EXPECT_NEAR(r.depth(p), 1 - d / radius, 0.05) << k << " " << d;
      EXPECT_NEAR(r.thickness(p), radius, 1.5) << k << " " << d;
    }
    EXPECT_EQ(r.depth(c + Eigen::Vector2d(radius + 1, 0)), 0);
    EXPECT_EQ(r.depth(c + Eigen::Vector2d(0, -radius - 1)), 0);
  }
  // Each region is blind to the other blob.
  EXPECT_EQ(regions[0].depth(c2), 0);
  EXPECT_EQ(regions[1].depth(c1), 0);
}

TEST(MaskRegion, BlobsAreEightConnectedInTheFirstChannel) {
  Image mask(10, 8, 3, 0);
  for (int k = 0; k < 2; ++k)  // two 2 x 2 squares touching at a corner: one blob
    for (int j = 0; j < 2; ++j) {
      mask.at(2 + k, 2 + j)[0] = 1;
      mask.at(4 + k, 4 + j)[0] = 200;
    }
  for (int k = 0; k < 4; ++k) mask.at(8, 1 + k)[1] = 255;  // second channel: not the mask
  const std::vector<Region> regions = Region::from_mask(mask);
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_TRUE(regions[0].bounds().isApprox(
      Eigen::AlignedBox2d(Eigen::Vector2d(2, 2), Eigen::Vector2d(6, 6))));
  EXPECT_GT(regions[0].depth({2.5, 2.5}), 0);
  EXPECT_EQ(regions[0].depth({8.5, 1.5}), 0);
}

TEST(MaskRegion, RejectsAnEmptyOrMalformedMask) {
  try {
    Region::from_mask(Image(10, 10, 1, 0));
    ADD_FAILURE() << "accepted an empty mask";
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(), "Region::from_mask: the mask has no non-zero pixel");
  }
  Image broken(4, 4, 1, 255);
  broken.pixels.pop_back();
  EXPECT_THROW(Region::from_mask(broken), InvalidInput);
  EXPECT_THROW(Region::from_mask(Image()), InvalidInput);
}

}  // namespace
}  // namespace geolens

namespace geolens {
namespace {

// A region moved is the region it was, read where it was: the same fields at p - offset, its
// outline, anchors, bounds and peak moved, its exact distance that of the polygon built where it
// now is; moved twice, it is moved once by the sum (not a region of a region); a circle stays a
// circle.
TEST(TranslatedRegion, IsTheRegionReadWhereItWas) {
  const std::vector<Eigen::Vector2d> l = {{100, 100}, {220, 100}, {220, 160},
                                          {160, 160}, {160, 260}, {100, 260}};
  const Region region = Region::polygon(l);
  const Eigen::Vector2d offset(37.25, -12.5);
  const Region moved = region.translated(Eigen::Vector2d(30, -10)).translated({7.25, -2.5});
  std::vector<Eigen::Vector2d> shifted = l;
  for (Eigen::Vector2d& v : shifted) v += offset;
  const Region rebuilt = Region::polygon(shifted);
  EXPECT_EQ(moved.kind(), "polygon");
  ASSERT_TRUE(moved.outline().has_value());
  for (size_t k = 0; k < l.size(); ++k) {
    EXPECT_LT(((*moved.outline())[k] - shifted[k]).norm(), 1e-12);
    EXPECT_LT((moved.anchors()[k] - shifted[k]).norm(), 1e-12);
  }
  EXPECT_LT((moved.peak() - (region.peak() + offset)).norm(), 1e-12);
  EXPECT_LT((moved.bounds().min() - rebuilt.bounds().min()).norm(), 1e-12);
  EXPECT_LT((moved.bounds().max() - rebuilt.bounds().max()).norm(), 1e-12);
  EXPECT_EQ(moved.size(), region.size());
  EXPECT_EQ(moved.reach(), region.reach());
  for (double x = 80; x < 300; x += 13.7) {
    for (double y = 60; y < 300; y += 11.3) {
      const Eigen::Vector2d p(x, y);
      EXPECT_EQ(moved.depth(p), region.depth(p - offset));
      EXPECT_EQ(moved.thickness(p), region.thickness(p - offset));
      EXPECT_NEAR(moved.distance(p), rebuilt.distance(p), 1e-9);
    }
  }
  const Region circle = Region::circle({50, 60}, 20).translated(offset);
  ASSERT_TRUE(circle.circle().has_value());
  EXPECT_LT((circle.circle()->center - Eigen::Vector2d(87.25, 47.5)).norm(), 1e-12);
  EXPECT_EQ(circle.circle()->radius, 20);
  EXPECT_THROW(region.translated({std::nan(""), 0}), InvalidInput);
}

}  // namespace
}  // namespace geolens
