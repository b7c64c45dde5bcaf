// The XYZ tile folder: each zoom read from its tiles, lazily; missing tiles made from a coarser
// zoom and counted; the folder rules and their refusals; a magnified region rendered from the
// deepest zoom.

#include "source/xyz_tiles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/io/image.h"
#include "geolens/render/render.h"
#include "geolens/source/source.h"
#include "geolens/source/source_file.h"
#include "geolens/warp/warp_mesh.h"
#include "source/downsample.h"
#include "support/scratch_folder.h"
#include "support/test_data.h"

using geolens::Image;
using geolens::InvalidInput;
using geolens::SourceFile;
using geolens::SourceFileOptions;
using geolens::TexelRegion;

namespace {

namespace fs = std::filesystem;

/// The world at zoom z, T 2^z texels square: texels that differ per zoom (channel 1) and per
/// position.
Image world(int z, int tile) {
  const int side = tile << z;
  Image image(side, side, 3);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      uint8_t* t = image.at(x, y);
      t[0] = uint8_t(x * 5 + y * 3);
      t[1] = uint8_t(60 * z + 10);
      t[2] = uint8_t(x * 9 + y * 13);
    }
  return image;
}

/// The counter `name` of `file`.
double counter(const SourceFile& file, const std::string& name) {
  for (const auto& [key, value] : file.counters())
    if (key == name) return value;
  ADD_FAILURE() << "no counter " << name;
  return -1;
}

class XyzTilesTest : public geolens::testing::ScratchFolderTest {
 protected:
  /// Writes `tile` as dir/z/x/y.EXT.
  void put(int z, int x, int y, const Image& tile, const std::string& ext = ".png") {
    fs::create_directories(dir_ / std::to_string(z) / std::to_string(x));
    geolens::save_image(
        (dir_ / std::to_string(z) / std::to_string(x) / (std::to_string(y) + ext)).string(), tile);
  }
  /// Writes tile (z, x, y) of `image` (the world at zoom z).
  void write_tile(const Image& image, int tile, int z, int x, int y) {
    put(z, x, y, geolens::test::crop(image, x * tile, y * tile, tile, tile));
  }
  /// Writes every tile of zoom z of `image`.
  void write_zoom(const Image& image, int tile, int z) {
    for (int y = 0; y < 1 << z; ++y)
      for (int x = 0; x < 1 << z; ++x) write_tile(image, tile, z, x, y);
  }
  /// The message opening the folder throws (fails the test if it does not).
  std::string refusal() {
    try {
      geolens::open_tile_folder(dir_.string());
    } catch (const InvalidInput& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("open_tile_folder: ", 0), 0u) << what;
      return what;
    }
    ADD_FAILURE() << "no exception";
    return "";
  }
};

/// Every texel of level `level` of `file`'s source in [x, x + w) x [y, y + h) equals
/// `expected`'s (whose texel (0, 0) is (x, y)) within `tolerance`.
void expect_texels(const SourceFile& file, int level, int x, int y, const Image& expected,
                   int tolerance = 0) {
  const TexelRegion region = file.source->fetch(level, x, y, expected.width, expected.height);
  for (int j = 0; j < expected.height; ++j)
    for (int i = 0; i < expected.width; ++i)
      for (int c = 0; c < expected.channels; ++c)
        ASSERT_NEAR(region.at(x + i, y + j)[c], expected.at(i, j)[c], tolerance)
            << "level " << level << " texel " << x + i << ", " << y + j << " channel " << c;
}

/// Bilinear upsampling of `coarse` by 2^d at the Source's texel centres, clamp-to-edge: texel
/// (X, Y) of the finer level at coarse coordinates ((X + 0.5) / 2^d - 0.5, ...).
Image upsampled(const Image& coarse, int d, int x, int y, int width, int height) {
  Image out(width, height, coarse.channels);
  const double step = std::ldexp(1.0, -d);
  auto at = [&](int cx, int cy, int c) {
    return double(
        coarse.at(std::clamp(cx, 0, coarse.width - 1), std::clamp(cy, 0, coarse.height - 1))[c]);
  };
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const double cx = (x + i + 0.5) * step - 0.5, cy = (y + j + 0.5) * step - 0.5;
      const int x0 = int(std::floor(cx)), y0 = int(std::floor(cy));
      const double fx = cx - x0, fy = cy - y0;
      for (int c = 0; c < coarse.channels; ++c) {
        const double top = at(x0, y0, c) * (1 - fx) + at(x0 + 1, y0, c) * fx;
        const double bottom = at(x0, y0 + 1, c) * (1 - fx) + at(x0 + 1, y0 + 1, c) * fx;
        out.at(i, j)[c] = uint8_t(std::lround(top * (1 - fy) + bottom * fy));
      }
    }
  return out;
}

}  // namespace

TEST_F(XyzTilesTest, EachLevelIsItsZoomsTilesAndPastTheRootTheRootDownsampled) {
  const int T = 16;
  std::vector<Image> zooms;
  for (int z = 0; z <= 3; ++z) {
    zooms.push_back(world(z, T));
    write_zoom(zooms.back(), T, z);
  }
  std::ofstream(dir_ / "README.txt") << "not a zoom";  // ignored, as are non-numeric folders
  fs::create_directories(dir_ / "metadata");
  const SourceFile file = geolens::open_source(dir_.string());
  EXPECT_EQ(file.kind, "tiles");
  EXPECT_EQ(file.source->width(), 128);
  EXPECT_EQ(file.source->height(), 128);
  ASSERT_EQ(file.source->levels(), 8);  // 128 .. 1
  for (int level = 0; level <= 3; ++level)
    expect_texels(file, level, 0, 0, zooms[size_t(3 - level)]);
  Image root = zooms[0];
  for (int level = 4; level < 8; ++level) {
    root = geolens::downsample(root);
    expect_texels(file, level, 0, 0, root);
  }
  EXPECT_EQ(counter(file, "missing_tiles"), 0);
  // Default frame: the zoom nearest 1024 px, here the deepest.
  EXPECT_EQ(file.frame_width, 128);
  EXPECT_EQ(file.frame_height, 128);
  EXPECT_EQ(file.scale, 1);
}

TEST_F(XyzTilesTest, AnAskedSizeFramesTheNearestZoom) {
  const int T = 16;
  for (int z = 0; z <= 3; ++z) write_tile(world(z, T), T, z, 0, 0);
  SourceFileOptions options;
  options.width = 40;  // 32 is 1.25x off, 64 1.6x
  SourceFile file = geolens::open_tile_folder(dir_.string(), options);
  EXPECT_EQ(file.frame_width, 32);
  EXPECT_EQ(file.frame_height, 32);
  EXPECT_EQ(file.scale, 4);
  options = {};
  options.height = 16;
  file = geolens::open_tile_folder(dir_.string(), options);
  EXPECT_EQ(file.frame_width, 16);
  EXPECT_EQ(file.scale, 8);
}

TEST_F(XyzTilesTest, ReadsOnlyTheTilesAFetchNeeds) {
  // Zoom 9 of 16 px tiles: 262144 potential tiles (a level of 8192 texels a side), of which the
  // folder holds a 2 x 2 block; the coarser zooms hold one tile each.
  const int T = 16;
  for (int z = 0; z < 9; ++z) write_tile(world(0, T), T, z, 0, 0);
  const Image deep = world(1, T);  // 32 x 32: tiles (100, 200) .. (101, 201) of zoom 9
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
      put(9, 100 + i, 200 + j, geolens::test::crop(deep, i * T, j * T, T, T));
  const SourceFile file = geolens::open_tile_folder(dir_.string());
  const auto& tiled = dynamic_cast<const geolens::TiledSource&>(*file.source);
  EXPECT_EQ(file.source->width(), 8192);
  EXPECT_EQ(counter(file, "tiles_read"), 1);  // the root, for the tile size
  expect_texels(file, 0, 1600, 3200, deep);
  EXPECT_EQ(counter(file, "tiles_read"), 5);
  EXPECT_EQ(tiled.cache_stats().tiles_made, 4u);
  EXPECT_EQ(counter(file, "missing_tiles"), 0);
  expect_texels(file, 0, 1600, 3200, deep);  // cached
  EXPECT_EQ(counter(file, "tiles_read"), 5);
  EXPECT_EQ(tiled.cache_stats().tiles_made, 4u);
}

TEST_F(XyzTilesTest, AMissingTileIsTheCoarserZoomUpsampledAndCounted) {
  const int T = 16;
  const Image z0 = world(0, T), z1 = world(1, T), z2 = world(2, T);
  write_zoom(z0, T, 0);
  write_zoom(z1, T, 1);
  write_tile(z2, T, 2, 0, 0);  // zoom 2 holds only its top-left tile
  write_tile(z2, T, 2, 1, 1);
  put(1, 1, 1, geolens::test::crop(z1, 16, 16, 16, 16),
      ".jpg");  // and zoom 1's last tile is a JPEG...
  fs::remove(dir_ / "1" / "1" / "1.png");
  fs::remove(dir_ / "1" / "0" / "1.png");  // ...and its bottom-left one is missing
  const SourceFile file = geolens::open_tile_folder(dir_.string());
  ASSERT_EQ(file.source->levels(), 7);  // 64 .. 1
  // Present tiles are themselves.
  expect_texels(file, 0, 0, 0, geolens::test::crop(z2, 0, 0, 16, 16));
  expect_texels(file, 0, 16, 16, geolens::test::crop(z2, 16, 16, 16, 16));
  EXPECT_EQ(counter(file, "missing_tiles"), 0);
  // Zoom 2's tile (2, 0) falls back to zoom 1's tile (1, 0): upsampled 2x.
  expect_texels(file, 0, 32, 0, upsampled(z1, 1, 32, 0, 16, 16), 1);
  EXPECT_EQ(counter(file, "missing_tiles"), 1);
  const TexelRegion fallback = file.source->fetch(0, 40, 8, 1, 1);
  EXPECT_EQ(fallback.data[1], 60 * 1 + 10);  // zoom 1's texels, not zoom 2's (130)
  // Zoom 2's tile (0, 3) lies under zoom 1's missing tile (0, 1): zoom 0's, upsampled 4x.
  expect_texels(file, 0, 0, 48, upsampled(z0, 2, 0, 48, 16, 16), 1);
  EXPECT_EQ(file.source->fetch(0, 5, 50, 1, 1).data[1], 10);
  EXPECT_EQ(counter(file, "missing_tiles"), 2);
  // The missing zoom 1 tile itself, fetched at its level.
  expect_texels(file, 1, 0, 16, upsampled(z0, 1, 0, 16, 16, 16), 1);
  EXPECT_EQ(counter(file, "missing_tiles"), 3);
  // The JPEG tile reads as zoom 1's texels (lossy: near).
  EXPECT_NEAR(file.source->fetch(1, 20, 20, 1, 1).data[1], 70, 4);
  EXPECT_EQ(counter(file, "missing_tiles"), 3);
}

TEST_F(XyzTilesTest, BadFoldersAreRefusedNamingTheFolderOrFile) {
  const int T = 16;
  fs::create_directories(dir_ / "tiles");
  std::string what = refusal();
  EXPECT_NE(what.find("'" + dir_.string() + "' has no zoom folders"), std::string::npos) << what;

  write_tile(world(0, T), T, 0, 0, 0);
  write_tile(world(2, T), T, 2, 1, 1);
  what = refusal();
  EXPECT_NE(what.find("no '" + (dir_ / "1").string() + "': a missing zoom level"),
            std::string::npos)
      << what;

  fs::remove_all(dir_ / "2");
  fs::remove_all(dir_ / "0");
  put(0, 0, 0, geolens::test::crop(world(1, T), 0, 0, 16, 8));
  what = refusal();
  EXPECT_NE(what.find("'" + (dir_ / "0" / "0" / "0.png").string() + "' is 16 x 8"),
            std::string::npos)
      << what;
  EXPECT_NE(what.find("square"), std::string::npos) << what;

  fs::remove_all(dir_ / "0");
  put(0, 0, 0, geolens::test::crop(world(1, T), 0, 0, 15, 15));
  what = refusal();
  EXPECT_NE(what.find("even"), std::string::npos) << what;

  // geolens's own layout, <level>/<x>_<y>.png, is recognized and named.
  fs::remove_all(dir_ / "0");
  fs::create_directories(dir_ / "0");
  geolens::save_image((dir_ / "0" / "0_0.png").string(), world(0, T));
  what = refusal();
  EXPECT_NE(what.find("'" + (dir_ / "0" / "0" / "0.png").string() + "' (the root tile) is missing"),
            std::string::npos)
      << what;
  EXPECT_NE(what.find("png_tile_folder"), std::string::npos) << what;

  EXPECT_THROW(geolens::open_tile_folder((dir_ / "absent").string()), InvalidInput);

  // Zoom folders 0 to 56 (empty but the root): refused by the zoom, before any size is shifted
  // by it (UndefinedBehaviorSanitizer had found a shift by 56).
  fs::remove_all(dir_ / "0");
  write_tile(world(0, T), T, 0, 0, 0);
  for (int z = 1; z <= 56; ++z) fs::create_directories(dir_ / std::to_string(z));
  what = refusal();
  EXPECT_NE(what.find("has a zoom folder 56: zooms above 30"), std::string::npos) << what;
}

// An entry of the folder whose type cannot be read (a dangling link) is no zoom folder, and the
// folder is read: its error had been kept as the listing's, so the folder was refused as
// "cannot be listed: No such file or directory" when such an entry was listed last.
TEST_F(XyzTilesTest, ADanglingLinkInTheFolderIsNoZoomFolder) {
  const int T = 16;
  write_zoom(world(0, T), T, 0);
  write_zoom(world(1, T), T, 1);
  for (int i = 0; i < 20; ++i)
    fs::create_symlink(dir_ / "gone", dir_ / ("link" + std::to_string(i)));
  try {
    const SourceFile file = geolens::open_tile_folder(dir_.string());
    EXPECT_EQ(file.frame_width, T << 1);
  } catch (const InvalidInput& e) {
    ADD_FAILURE() << e.what();
  }
}

TEST_F(XyzTilesTest, ATileOfAnotherSizeIsRefusedWhenFetchedNamingIt) {
  const int T = 16;
  write_zoom(world(0, T), T, 0);
  write_zoom(world(1, T), T, 1);
  fs::remove(dir_ / "1" / "1" / "0.png");
  put(1, 1, 0, geolens::test::crop(world(1, 8), 0, 0, 8, 8));
  const SourceFile file = geolens::open_tile_folder(dir_.string());
  expect_texels(file, 0, 0, 0, geolens::test::crop(world(1, T), 0, 0, 16, 16));
  try {
    file.source->fetch(0, 20, 0, 4, 4);
    ADD_FAILURE() << "no exception";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("open_tile_folder: '" + (dir_ / "1" / "1" / "0.png").string() +
                             "' is 8 x 8, but the tiles of",
                         0),
              0u)
        << what;
    EXPECT_NE(what.find("mixed sizes"), std::string::npos) << what;
  }
}

TEST_F(XyzTilesTest, AMagnifiedRegionOfTheCoarseFrameSamplesTheDeepestZoom) {
  // Zoom 2 (128 texels) has 2-texel stripes, which zoom 0 (a quarter) averages to flat grey.
  const int T = 32;
  Image fine(128, 128, 1);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) fine.at(x, y)[0] = ((x + y / 8) / 2) % 2 ? 230 : 20;
  const Image half = geolens::downsample(fine), coarse = geolens::downsample(half);
  write_zoom(coarse, T, 0);
  write_zoom(half, T, 1);
  write_zoom(fine, T, 2);
  SourceFileOptions options;
  options.width = 32;
  const SourceFile file = geolens::open_source(dir_.string(), options);
  ASSERT_EQ(file.frame_width, 32);
  ASSERT_EQ(file.scale, 4);

  // The identity on the 32 x 32 frame, with the frame's [12, 20]^2 magnified 4x onto the
  // screen's [0, 32]^2 drawn over it: the whole output is the lens.
  const geolens::WarpMesh mesh = geolens::test::magnified_patch(32, {12, 12}, 8, {0, 0}, 32);

  geolens::RenderOptions render_options;
  render_options.width = render_options.height = 32;
  render_options.source_scale = file.scale;
  const Image out = geolens::render(mesh, *file.source, render_options);
  ASSERT_EQ(out.channels, 1);
  // Output pixel (x, y) is at frame point 12 + (x + 0.5) / 4: the fine texel (48 + x, 48 + y).
  double error = 0, magnified_coarse_error = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const int expected = fine.at(48 + x, 48 + y)[0];
      error += std::abs(out.at(x, y)[0] - expected);
      magnified_coarse_error += std::abs(coarse.at(12 + x / 4, 12 + y / 4)[0] - expected);
    }
  EXPECT_LT(error / (32 * 32), 3.0);
  // Magnifying the coarse frame instead would be far off: it has no stripes.
  EXPECT_GT(magnified_coarse_error / (32 * 32), 60.0);
  EXPECT_EQ(counter(file, "missing_tiles"), 0);
}

TEST_F(XyzTilesTest, ThreadsFetchingAtOnceMakeEachMissingTileOnce) {
  // Zoom 3 holds one tile in four; the others fall back to zoom 2, as fetched alone.
  const int T = 16;
  const Image z3 = world(3, T);
  for (int z = 0; z <= 2; ++z) write_zoom(world(z, T), T, z);
  for (int y = 0; y < 8; y += 2)
    for (int x = 0; x < 8; x += 2) write_tile(z3, T, 3, x, y);
  const SourceFile alone = geolens::open_tile_folder(dir_.string());
  const TexelRegion expected_region = alone.source->fetch(0, 0, 0, 128, 128);
  Image expected(128, 128, 3);
  for (int y = 0; y < 128; ++y) std::copy_n(expected_region.at(0, y), 128 * 3, expected.at(0, y));
  EXPECT_EQ(counter(alone, "missing_tiles"), 48);

  const SourceFile file = geolens::open_tile_folder(dir_.string());
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([&, t] {
      // Each thread visits the 64 tiles of zoom 3 in its own order, a region of 3 x 3 texels
      // across tile corners at a time (so fallbacks fetch coarser tiles re-entrantly).
      for (int k = 0; k < 64; ++k) {
        const int tile = (k * 13 + t * 7) % 64;
        file.source->fetch(0, (tile % 8) * T - 1, (tile / 8) * T - 1, 3, 3);
      }
    });
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(counter(file, "missing_tiles"), 48);  // each made once
  expect_texels(file, 0, 0, 0, expected);
}
