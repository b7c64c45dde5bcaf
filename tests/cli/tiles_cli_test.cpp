// `geolens magnify` on a tile folder and a level list through the real binary: the frame and
// scale, the missing tiles counted in --stats, and one-line refusals with exit 2 and nothing
// written.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "geolens/io/image.h"
#include "support/cli_test.h"

namespace geolens {
namespace {

namespace fs = std::filesystem;

using testing::CliRun;

/// A T x T tile of one grey level.
Image flat_tile(int size, uint8_t grey) { return Image(size, size, 3, grey); }

class TilesCli : public testing::CliTest {
 protected:
  /// Writes `tile` as tiles/z/x/y.png.
  void put(int z, int x, int y, const Image& tile) const {
    const fs::path column = dir_ / "tiles" / std::to_string(z) / std::to_string(x);
    fs::create_directories(column);
    save_image((column / (std::to_string(y) + ".png")).string(), tile);
  }
  /// Zooms 0 and 1 complete (grey 100 and 150), zoom 2 only its tile (1, 1) (grey 200): 32 px
  /// tiles.
  void SetUp() override {
    testing::CliTest::SetUp();
    put(0, 0, 0, flat_tile(32, 100));
    for (int x = 0; x < 2; ++x)
      for (int y = 0; y < 2; ++y) put(1, x, y, flat_tile(32, 150));
    put(2, 1, 1, flat_tile(32, 200));
  }
  nlohmann::json stats() const {
    std::ifstream in(path("stats.json"));
    return nlohmann::json::parse(in);
  }
};

TEST_F(TilesCli, MagnifiesATileFolderAtTheAskedFrameAndCountsTheMissingTiles) {
  const CliRun r = run("magnify " + path("tiles") + " --size 64x64 --lens circle:24,24,6:2 -o " +
                       path("out.png") + " --stats " + path("stats.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const Image out = load_image(path("out.png"));
  EXPECT_EQ(out.width, 64);
  EXPECT_EQ(out.height, 64);
  const nlohmann::json source = stats().at("source");
  EXPECT_EQ(source.at("kind"), "tiles");
  EXPECT_EQ(source.at("scale"), 2.0);
  // The focus, magnified 2x from zoom 1, reads zoom 2's tile (1, 1); the context is zoom 1.
  EXPECT_EQ(source.at("missing_tiles"), 0.0);
  EXPECT_GE(source.at("tiles_read").get<double>(), 2);
  EXPECT_EQ(out.at(24, 24)[0], 200);
  EXPECT_EQ(out.at(2, 2)[0], 150);
  // A focus over zoom 2's missing tile (2, 2) reads it made from zoom 1, and counts it.
  ASSERT_EQ(run("magnify " + path("tiles") + " --size 64x64 --lens circle:44,44,6:2 -o " +
                path("out.png") + " --stats " + path("stats.json"))
                .code,
            0);
  EXPECT_GT(stats().at("source").at("missing_tiles").get<double>(), 0);
  EXPECT_EQ(load_image(path("out.png")).at(44, 44)[0], 150);
}

// An output inside the input tile folder (a tile, or a new file among them) is refused before
// any work: it had overwritten the tile it named.
TEST_F(TilesCli, RefusesAnOutputInsideTheInputTileFolder) {
  expect_refused("magnify " + path("tiles") + " --size 64x64 --lens circle:24,24,6:2 -o " +
                     path("tiles/2/1/1.png"),
                 "--output: '" + path("tiles/2/1/1.png") + "' is inside the input tile folder");
  expect_refused("magnify " + path("tiles") + " --size 64x64 --lens circle:24,24,6:2 -o " +
                     path("out.png") + " --stats " + path("tiles/stats.json"),
                 "--stats: '" + path("tiles/stats.json") + "' is inside the input tile folder");
}

TEST_F(TilesCli, MagnifiesALevelList) {
  save_image(path("fine.png"), flat_tile(128, 60));
  save_image(path("coarse.png"), flat_tile(32, 90));
  std::ofstream(path("map.levels")) << "fine.png\ncoarse.png\n";
  const CliRun r = run("magnify " + path("map.levels") + " --lens circle:16,16,3:2 -o " +
                       path("out.png") + " --stats " + path("stats.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const Image out = load_image(path("out.png"));
  EXPECT_EQ(out.width, 32);  // the coarsest image frames it
  const nlohmann::json source = stats().at("source");
  EXPECT_EQ(source.at("kind"), "level list");
  EXPECT_EQ(source.at("scale"), 4.0);
  EXPECT_EQ(out.at(16, 16)[0], 60);  // the focus reads a level made from the fine image
  EXPECT_EQ(out.at(1, 1)[0], 90);
  // A level image is an input: an output naming it is refused before any work (it was
  // overwritten).
  expect_refused(
      "magnify " + path("map.levels") + " --lens circle:16,16,3:2 -o " + path("coarse.png"),
      "--output: '" + path("coarse.png") + "' would overwrite part of the input '" +
          path("map.levels") + "' '" + path("coarse.png") + "'");
}

TEST_F(TilesCli, BadTileFoldersAndLevelListsAreRefusedInOneLine) {
  const std::string lens =
      " --lens circle:32,32,6:2 -o " + path("out.png") + " --stats " + path("stats.json");
  // A tile of another size, found when the focus reads it.
  put(2, 1, 2, flat_tile(16, 200));
  expect_refused("magnify " + path("tiles") + " --size 64x64" + lens,
                 (dir_ / "tiles" / "2" / "1" / "2.png").string() + "' is 16 x 16");
  // A zoom missing between 0 and the deepest.
  fs::remove_all(dir_ / "tiles" / "1");
  expect_refused("magnify " + path("tiles") + lens, "a missing zoom level");
  // A level list whose extents disagree.
  save_image(path("fine.png"), flat_tile(128, 60));
  save_image(path("flat.png"), Image(64, 40, 3, 90));
  std::ofstream(path("bad.levels")) << "fine.png\n# the coarse one\nflat.png\n";
  expect_refused("magnify " + path("bad.levels") + lens, "line 3: 'flat.png' is 64 x 40");
}

}  // namespace
}  // namespace geolens
