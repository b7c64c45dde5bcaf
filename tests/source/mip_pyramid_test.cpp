// The mip pyramid as a Source (its levels and sampling are tested in render/render_test.cpp).

#include <gtest/gtest.h>

#include "geolens/core/errors.h"
#include "geolens/source/source.h"
#include "source/downsample.h"

using geolens::Image;
using geolens::MipPyramid;
using geolens::TexelRegion;

TEST(MipPyramidSourceTest, FetchInsideALevelIsAViewWithoutACopy) {
  Image image(40, 30, 3);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = uint8_t(i * 31);
  const MipPyramid pyramid(image);
  for (int level = 0; level < pyramid.levels(); ++level) {
    const Image& l = pyramid.level(level);
    const TexelRegion whole = pyramid.fetch(level, 0, 0, l.width, l.height);
    EXPECT_EQ(whole.data, l.pixels.data()) << level;
    EXPECT_EQ(whole.stride, size_t(l.width) * 3);
    EXPECT_FALSE(whole.owner);
    const TexelRegion part = pyramid.fetch(level, l.width / 2, l.height / 2, 1, 1);
    EXPECT_EQ(part.data, l.at(l.width / 2, l.height / 2)) << level;
    EXPECT_FALSE(part.owner);
  }
  // Outside the level: a clamped copy, kept alive by the region.
  EXPECT_TRUE(pyramid.fetch(0, -1, 0, 2, 2).owner);
}

TEST(MipPyramidSourceTest, EachLevelIsTheDownsampleOfThePrevious) {
  Image image(37, 11, 2);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = uint8_t(i * 7 + i / 5);
  const MipPyramid pyramid(image);
  for (int level = 1; level < pyramid.levels(); ++level)
    EXPECT_EQ(pyramid.level(level).pixels, geolens::downsample(pyramid.level(level - 1)).pixels)
        << level;
}

TEST(DownsampleTest, RejectsAnInvalidImage) {
  EXPECT_THROW(geolens::downsample(Image()), geolens::InvalidInput);
  Image broken(4, 4, 3);
  broken.pixels.resize(5);
  EXPECT_THROW(geolens::downsample(broken), geolens::InvalidInput);
}
