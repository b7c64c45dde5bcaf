// The Source contract, checked on both implementations: level sizes, clamp-to-edge fetches,
// argument checks.

#include "geolens/source/source.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "geolens/core/errors.h"
#include "support/test_data.h"

using geolens::Image;
using geolens::InvalidInput;
using geolens::MipPyramid;
using geolens::Source;
using geolens::TexelRegion;
using geolens::TiledSource;
using geolens::TiledSourceOptions;
using geolens::TileRequest;

namespace {

/// A tiled source serving the levels of `pyramid`, cut into 8 x 8 tiles.
std::unique_ptr<TiledSource> tiled(const MipPyramid& pyramid) {
  TiledSourceOptions options;
  options.tile_size = 8;
  options.cache_bytes = 4 * 8 * 8 * size_t(pyramid.channels());
  return std::make_unique<TiledSource>(
      pyramid.width(), pyramid.height(), pyramid.channels(),
      [&pyramid](const TileRequest& r) {
        const Image& level = pyramid.level(r.level);
        Image tile(r.width, r.height, r.channels);
        for (int j = 0; j < r.height; ++j)
          std::copy(level.at(r.x, r.y + j), level.at(r.x + r.width, r.y + j), tile.at(0, j));
        return tile;
      },
      options);
}

/// Every texel of `region` equals the level's texel at the clamped coordinates.
void expect_clamped(const MipPyramid& pyramid, int level, const TexelRegion& region) {
  const Image& image = pyramid.level(level);
  ASSERT_EQ(region.channels, image.channels);
  for (int j = 0; j < region.height; ++j)
    for (int i = 0; i < region.width; ++i) {
      const int x = std::clamp(region.x + i, 0, image.width - 1);
      const int y = std::clamp(region.y + j, 0, image.height - 1);
      const uint8_t* got = region.at(region.x + i, region.y + j);
      ASSERT_TRUE(std::equal(got, got + image.channels, image.at(x, y)))
          << "level " << level << " texel " << region.x + i << ", " << region.y + j;
    }
}

}  // namespace

TEST(SourceTest, LevelsHalveRoundingUpDownTo1x1AsTheMipPyramidDoes) {
  const MipPyramid pyramid(geolens::test::pattern(37, 10, 3));
  const std::unique_ptr<TiledSource> tiles = tiled(pyramid);
  for (const Source* source :
       {static_cast<const Source*>(&pyramid), static_cast<const Source*>(tiles.get())}) {
    EXPECT_EQ(source->width(), 37);
    EXPECT_EQ(source->height(), 10);
    EXPECT_EQ(source->channels(), 3);
    ASSERT_EQ(source->levels(), 7);  // 37, 19, 10, 5, 3, 2, 1
    for (int l = 0; l < source->levels(); ++l) {
      EXPECT_EQ(source->level_width(l), pyramid.level(l).width) << l;
      EXPECT_EQ(source->level_height(l), pyramid.level(l).height) << l;
    }
  }
  const TiledSource huge(32768, 32768, 3,
                         [](const TileRequest& r) { return Image(r.width, r.height, r.channels); });
  EXPECT_EQ(huge.levels(), 16);
  EXPECT_EQ(huge.level_width(15), 1);
  EXPECT_EQ(TiledSource(1, 1, 1,
                        [](const TileRequest& r) { return Image(r.width, r.height, r.channels); })
                .levels(),
            1);
}

TEST(SourceTest, FetchReturnsTheTexelsAndClampsOutsideTheExtent) {
  const MipPyramid pyramid(geolens::test::pattern(37, 21, 2));
  const std::unique_ptr<TiledSource> tiles = tiled(pyramid);
  struct Rect {
    int x, y, width, height;
  };
  const std::vector<Rect> rects = {{0, 0, 37, 21},       {3, 5, 4, 4},      {5, 2, 20, 13},
                                   {-6, -4, 12, 9},      {30, 15, 15, 12},  {-100, 3, 5, 2},
                                   {3, 500, 2, 3},       {-3, -3, 50, 40},  {36, 20, 1, 1},
                                   {-1000, -1000, 1, 1}, {1000, 1000, 2, 2}};
  for (const Source* source :
       {static_cast<const Source*>(&pyramid), static_cast<const Source*>(tiles.get())})
    for (int level = 0; level < source->levels(); ++level)
      for (const Rect& r : rects) {
        const TexelRegion region = source->fetch(level, r.x, r.y, r.width, r.height);
        EXPECT_EQ(region.x, r.x);
        EXPECT_EQ(region.y, r.y);
        EXPECT_EQ(region.width, r.width);
        EXPECT_EQ(region.height, r.height);
        expect_clamped(pyramid, level, region);
      }
}

TEST(SourceTest, FetchRejectsInvalidArguments) {
  const MipPyramid pyramid(geolens::test::pattern(16, 8, 1));
  const std::unique_ptr<TiledSource> tiles = tiled(pyramid);
  for (const Source* source :
       {static_cast<const Source*>(&pyramid), static_cast<const Source*>(tiles.get())}) {
    EXPECT_THROW(source->fetch(-1, 0, 0, 1, 1), InvalidInput);
    EXPECT_THROW(source->fetch(source->levels(), 0, 0, 1, 1), InvalidInput);
    EXPECT_THROW(source->fetch(0, 0, 0, 0, 1), InvalidInput);
    EXPECT_THROW(source->fetch(0, 0, 0, 4, -2), InvalidInput);
    EXPECT_THROW(source->fetch(0, 0, 0, 1 << 16, 1 << 15), InvalidInput);  // 2^31 texels
    try {
      source->fetch(7, 0, 0, 1, 1);
      ADD_FAILURE() << "no exception";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("Source::fetch"), std::string::npos) << e.what();
    }
  }
}
