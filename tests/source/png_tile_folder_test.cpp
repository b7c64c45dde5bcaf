#include "source/png_tile_folder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/source/source.h"
#include "support/scratch_folder.h"
#include "support/test_data.h"

using geolens::Image;
using geolens::InvalidInput;
using geolens::TexelRegion;

namespace {

using PngTileFolderTest = geolens::testing::ScratchFolderTest;

Image pattern(int width, int height) {
  Image image(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) image.at(x, y)[c] = uint8_t(x * 5 + y * 3 + c * 80);
  return image;
}

/// Writes the level-0 tiles of `image` (tile_size x tile_size) to `dir` as png_tile_folder
/// reads them.
void write_level0(const Image& image, int tile_size, const std::string& dir) {
  std::filesystem::create_directories(std::filesystem::path(dir) / "0");
  for (int ty = 0; ty * tile_size < image.height; ++ty)
    for (int tx = 0; tx * tile_size < image.width; ++tx) {
      const int x = tx * tile_size, y = ty * tile_size;
      geolens::save_image(geolens::png_tile_path(dir, 0, tx, ty),
                          geolens::test::crop(image, x, y, std::min(tile_size, image.width - x),
                                              std::min(tile_size, image.height - y)));
    }
}

}  // namespace

TEST_F(PngTileFolderTest, ReadsTilesAndDownsamplesTheLevelsAsTheMipPyramid) {
  const Image image = pattern(70, 45);
  write_level0(image, 32, dir_.string());
  EXPECT_EQ(geolens::png_tile_path(dir_.string(), 0, 2, 1), path("0/2_1.png"));
  geolens::TiledSourceOptions options;
  options.tile_size = 32;
  options.downsample_levels = true;
  const geolens::TiledSource source(70, 45, 3, geolens::png_tile_folder(dir_.string()), options);
  const geolens::MipPyramid pyramid(image);
  for (int level = 0; level < pyramid.levels(); ++level) {
    const Image& expected = pyramid.level(level);
    const TexelRegion region = source.fetch(level, 0, 0, expected.width, expected.height);
    for (int y = 0; y < expected.height; ++y)
      ASSERT_TRUE(
          std::equal(region.at(0, y), region.at(0, y) + expected.width * 3, expected.at(0, y)))
          << level << ", " << y;
  }
}

TEST_F(PngTileFolderTest, AMissingOrWrongTileNamesTheFunctionAndTheFile) {
  write_level0(pattern(40, 40), 32, dir_.string());
  const geolens::TileProvider provider = geolens::png_tile_folder(dir_.string());
  // The provider's message for `request`: it must name the function and every one of `parts`.
  auto expect_refused = [&](const geolens::TileRequest& request,
                            const std::vector<std::string>& parts) {
    try {
      provider(request);
      ADD_FAILURE() << "no exception";
    } catch (const InvalidInput& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("png_tile_folder: ", 0), 0u) << what;
      for (const std::string& part : parts) EXPECT_NE(what.find(part), std::string::npos) << what;
    }
  };
  geolens::TileRequest request;
  request.level = 1;  // not written
  request.width = request.height = 20;
  request.channels = 3;
  expect_refused(request, {path("1/0_0.png")});
  request.level = 0;
  request.tile_x = 1;  // 8 x 32 on disk
  request.width = 32;
  request.height = 32;
  expect_refused(request, {path("0/1_0.png"), "8 x 32"});
  // Through a source whose tile size disagrees with the files.
  geolens::TiledSourceOptions options;
  options.tile_size = 16;
  const geolens::TiledSource source(40, 40, 3, provider, options);
  EXPECT_THROW(source.fetch(0, 0, 0, 4, 4), InvalidInput);
}
