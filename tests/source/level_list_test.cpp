// The level list: each level read from its image or downsampled, lazily, with a bounded cache;
// the size rules and their refusals; a magnified region rendered from the finest level.

#include "source/level_list.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/io/image.h"
#include "geolens/render/render.h"
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

using LevelListTest = geolens::testing::ScratchFolderTest;

/// A width x height RGB image whose texels differ per `tag` (so a test can tell which image a
/// level came from) and per position.
Image tagged(int width, int height, int tag) {
  Image image(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      uint8_t* t = image.at(x, y);
      t[0] = uint8_t(x * 7 + y * 3);
      t[1] = uint8_t(50 * tag + 20);
      t[2] = uint8_t(x * 2 + y * 11 + tag * 31);
    }
  return image;
}

/// Every texel of level `level` of `file`'s source equals `expected`'s.
void expect_level(const SourceFile& file, int level, const Image& expected) {
  ASSERT_EQ(file.source->level_width(level), expected.width) << level;
  ASSERT_EQ(file.source->level_height(level), expected.height) << level;
  ASSERT_EQ(file.source->channels(), expected.channels);
  const TexelRegion region = file.source->fetch(level, 0, 0, expected.width, expected.height);
  for (int y = 0; y < expected.height; ++y)
    for (int x = 0; x < expected.width; ++x)
      for (int c = 0; c < expected.channels; ++c)
        ASSERT_EQ(region.at(x, y)[c], expected.at(x, y)[c])
            << "level " << level << " texel " << x << ", " << y << " channel " << c;
}

/// The counter `name` of `file`.
double counter(const SourceFile& file, const std::string& name) {
  for (const auto& [key, value] : file.counters())
    if (key == name) return value;
  ADD_FAILURE() << "no counter " << name;
  return -1;
}

class LevelListFiles : public LevelListTest {
 protected:
  /// Writes `text` as the list `name` and returns its path.
  std::string list(const std::string& text, const std::string& name = "pyramid.levels") {
    std::ofstream(path(name)) << text;
    return path(name);
  }
  /// Writes `image` as `name` in the scratch folder.
  void write(const std::string& name, const Image& image) {
    geolens::save_image(path(name), image);
  }
  /// The message open_level_list throws for `list_path` (fails the test if it does not).
  std::string refusal(const std::string& list_path) {
    try {
      geolens::open_level_list(list_path);
    } catch (const InvalidInput& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("open_level_list: '" + list_path + "'", 0), 0u) << what;
      return what;
    }
    ADD_FAILURE() << "no exception for " << list_path;
    return "";
  }
};

}  // namespace

TEST_F(LevelListFiles, GivenLevelsAreTheirImagesAndTheOthersAreDownsampled) {
  const Image fine = tagged(64, 48, 0), coarse = tagged(16, 12, 2);
  write("fine.png", fine);
  write("coarse.png", coarse);
  // In any order, with comments, blanks and surrounding spaces.
  const std::string levels = list("# a pyramid\n\n  coarse.png  \n# the finest\nfine.png\n");
  const SourceFile file = geolens::open_source(levels);
  EXPECT_EQ(file.kind, "level list");
  EXPECT_EQ(file.source->width(), 64);
  EXPECT_EQ(file.source->height(), 48);
  EXPECT_EQ(file.source->levels(), 7);  // 64 .. 1
  expect_level(file, 0, fine);
  expect_level(file, 1, geolens::downsample(fine));
  expect_level(file, 2, coarse);
  expect_level(file, 3, geolens::downsample(coarse));
  expect_level(
      file, 6,
      geolens::downsample(geolens::downsample(geolens::downsample(geolens::downsample(coarse)))));
  // The default frame is the coarsest image, at a power-of-two scale.
  EXPECT_EQ(file.frame_width, 16);
  EXPECT_EQ(file.frame_height, 12);
  EXPECT_EQ(file.scale, 4);
}

TEST_F(LevelListFiles, AnAskedSizeFramesTheNearestLevel) {
  write("fine.png", tagged(64, 48, 0));
  write("coarse.png", tagged(8, 6, 3));
  const std::string levels = list("fine.png\ncoarse.png\n");
  SourceFileOptions options;
  options.width = 40;  // 32 is 1.25x off, 64 1.6x
  SourceFile file = geolens::open_level_list(levels, options);
  EXPECT_EQ(file.frame_width, 32);
  EXPECT_EQ(file.frame_height, 24);
  EXPECT_EQ(file.scale, 2);
  options = {};
  options.height = 50;  // by height when no width is asked
  file = geolens::open_level_list(levels, options);
  EXPECT_EQ(file.frame_height, 48);
  EXPECT_EQ(file.scale, 1);
}

TEST_F(LevelListFiles, DecodesAnImageOnlyWhenItsLevelIsFetchedAndKeepsToTheBudget) {
  const Image fine = tagged(64, 64, 0), middle = tagged(32, 32, 1), coarse = tagged(8, 8, 3);
  write("fine.png", fine);
  write("middle.png", middle);
  write("coarse.png", coarse);
  const std::string levels = list("fine.png\nmiddle.png\ncoarse.png\n");
  // A budget of one fine level: fetching another level evicts it.
  const SourceFile file = geolens::open_level_list(levels, {}, 64 * 64 * 3);
  EXPECT_EQ(counter(file, "images_decoded"), 1);  // the coarsest, for its channels
  expect_level(file, 3, coarse);
  EXPECT_EQ(counter(file, "images_decoded"), 1);
  expect_level(file, 0, fine);
  EXPECT_EQ(counter(file, "images_decoded"), 2);  // middle.png still unread
  expect_level(file, 0, fine);
  EXPECT_EQ(counter(file, "images_decoded"), 2);  // cached
  expect_level(file, 2, geolens::downsample(middle));
  EXPECT_EQ(counter(file, "images_decoded"), 3);  // level 2 needs level 1's image
  EXPECT_EQ(counter(file, "levels_made"), 1);
  expect_level(file, 0, fine);
  EXPECT_EQ(counter(file, "images_decoded"), 4);  // evicted, decoded again
}

TEST_F(LevelListFiles, ImagesATexelShortAndJpegsAreAccepted) {
  // 63 x 47 halves to 32 x 24 rounding up; a 31 x 23 image (rounded down) repeats its edge.
  const Image fine = tagged(63, 47, 0), half = tagged(31, 23, 1);
  write("fine.png", fine);
  write("half.png", half);
  write("quarter.jpg", tagged(16, 12, 2));
  const SourceFile file = geolens::open_level_list(list("fine.png\nhalf.png\nquarter.jpg\n"));
  ASSERT_EQ(file.source->level_width(1), 32);
  ASSERT_EQ(file.source->level_height(1), 24);
  const TexelRegion region = file.source->fetch(1, 0, 0, 32, 24);
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(region.at(x, y)[c], half.at(std::min(x, 30), std::min(y, 22))[c])
            << x << ", " << y;
  // The JPEG's size came from its header: the frame is its level, 16 x 12.
  EXPECT_EQ(file.frame_width, 16);
  EXPECT_EQ(file.scale, 4);
  const TexelRegion jpeg = file.source->fetch(2, 0, 0, 16, 12);
  EXPECT_NEAR(jpeg.at(5, 5)[1], 50 * 2 + 20, 8);  // the JPEG's tag, not a downsampled level's
}

TEST_F(LevelListFiles, AnImageMayBeALevelWhereOneSideIsDownToOneTexel) {
  write("tall.png", tagged(4, 64, 0));
  write("top.png", tagged(1, 16, 1));  // level 2: 1 x 16; and level 6 is 1 x 1
  write("one.png", tagged(1, 1, 2));
  const SourceFile file = geolens::open_level_list(list("tall.png\ntop.png\none.png\n"));
  ASSERT_EQ(file.source->levels(), 7);
  expect_level(file, 2, tagged(1, 16, 1));
  expect_level(file, 4, geolens::downsample(geolens::downsample(tagged(1, 16, 1))));
  expect_level(file, 6, tagged(1, 1, 2));
  EXPECT_EQ(file.frame_width, 1);
  EXPECT_EQ(file.frame_height, 1);
  EXPECT_EQ(file.scale, 64);
}

TEST_F(LevelListFiles, ChannelsAreTheCoarsestImagesAndOthersAreConverted) {
  Image grey(8, 8, 1);
  for (int i = 0; i < 64; ++i) grey.pixels[size_t(i)] = uint8_t(i * 3);
  write("fine.png", tagged(16, 16, 0));
  write("coarse.png", grey);
  const SourceFile file = geolens::open_level_list(list("fine.png\ncoarse.png\n"));
  ASSERT_EQ(file.source->channels(), 1);
  const Image fine = tagged(16, 16, 0);
  const TexelRegion region = file.source->fetch(0, 3, 2, 1, 1);
  const uint8_t* rgb = fine.at(3, 2);
  EXPECT_NEAR(region.data[0], 0.299 * rgb[0] + 0.587 * rgb[1] + 0.114 * rgb[2], 0.51);
}

TEST_F(LevelListFiles, BadListsAreRefusedNamingTheLine) {
  write("fine.png", tagged(64, 48, 0));
  write("flat.png", tagged(32, 20, 1));   // half the width, not half the height
  write("third.png", tagged(21, 16, 1));  // no halving of 64
  write("half.png", tagged(32, 24, 1));
  write("half2.png", tagged(32, 24, 2));
  std::ofstream(path("notes.png")) << "not an image";

  std::string what = refusal(list("fine.png\n\nflat.png\n", "aspect.levels"));
  EXPECT_NE(what.find("line 3: 'flat.png' is 32 x 20"), std::string::npos) << what;
  EXPECT_NE(what.find("disagree"), std::string::npos) << what;

  what = refusal(list("fine.png\nthird.png\n", "third.levels"));
  EXPECT_NE(what.find("line 2: 'third.png' is 21 x 16"), std::string::npos) << what;
  EXPECT_NE(what.find("halved"), std::string::npos) << what;

  what = refusal(list("half.png\nfine.png\nhalf2.png\n", "twice.levels"));
  EXPECT_NE(what.find("'half.png' (line 1) and 'half2.png' (line 3) are both level 1"),
            std::string::npos)
      << what;

  what = refusal(list("fine.png\nmissing.png\n", "missing.levels"));
  EXPECT_NE(what.find("line 2: 'missing.png' cannot be opened"), std::string::npos) << what;

  what = refusal(list("fine.png\nnotes.png\n", "notes.levels"));
  EXPECT_NE(what.find("line 2: 'notes.png' is not a PNG or JPEG"), std::string::npos) << what;

  what = refusal(list("# nothing\n\n", "empty.levels"));
  EXPECT_NE(what.find("names no image"), std::string::npos) << what;

  EXPECT_THROW(geolens::open_level_list(path("absent.levels")), InvalidInput);
}

TEST_F(LevelListFiles, AMagnifiedRegionOfTheCoarseFrameSamplesTheFinestLevel) {
  // Fine: 2-texel stripes, which the coarse level (a quarter) averages to flat grey.
  Image fine(256, 256, 1);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) fine.at(x, y)[0] = ((x + y / 8) / 2) % 2 ? 230 : 20;
  const Image coarse = geolens::downsample(geolens::downsample(fine));
  write("fine.png", fine);
  write("coarse.png", coarse);
  const SourceFile file = geolens::open_level_list(list("coarse.png\nfine.png\n"));
  ASSERT_EQ(file.frame_width, 64);
  ASSERT_EQ(file.scale, 4);

  // The identity on the 64 x 64 frame, with the frame's [28, 36]^2 magnified 4x onto the
  // screen's [16, 48]^2 drawn over it.
  const geolens::WarpMesh mesh = geolens::test::magnified_patch(64, {28, 28}, 8, {16, 16}, 32);

  geolens::RenderOptions options;
  options.width = options.height = 64;
  options.source_scale = file.scale;
  const Image out = geolens::render(mesh, *file.source, options);
  ASSERT_EQ(out.channels, 1);
  // Inside the lens: the fine texels (96 + i, 96 + j), each on one output pixel.
  double lens_error = 0, context_error = 0, magnified_coarse_error = 0;
  int lens_count = 0, context_count = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool in_lens = x >= 17 && x < 47 && y >= 17 && y < 47;  // a pixel off the edges
      const bool in_context = x < 15 || x >= 49 || y < 15 || y >= 49;
      if (in_lens) {
        lens_error += std::abs(out.at(x, y)[0] - fine.at(96 + x, 96 + y)[0]);
        // The coarse texel under the pixel's centre, at frame point 28 + (x + 0.5 - 16) / 4.
        const int coarse_x = int(28 + (x + 0.5 - 16) / 4), coarse_y = int(28 + (y + 0.5 - 16) / 4);
        magnified_coarse_error +=
            std::abs(fine.at(96 + x, 96 + y)[0] - coarse.at(coarse_x, coarse_y)[0]);
        ++lens_count;
      } else if (in_context) {
        context_error += std::abs(out.at(x, y)[0] - coarse.at(x, y)[0]);
        ++context_count;
      }
    }
  EXPECT_LT(lens_error / lens_count, 3.0);
  EXPECT_LT(context_error / context_count, 3.0);
  // Magnifying the coarse frame instead would be far off: it has no stripes.
  EXPECT_GT(magnified_coarse_error / lens_count, 60.0);
}
