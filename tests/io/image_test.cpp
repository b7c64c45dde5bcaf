#include "geolens/io/image.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "support/refusal.h"
#include "support/scratch_folder.h"
#include "support/test_data.h"

namespace fs = std::filesystem;
using geolens::Image;
using geolens::InvalidInput;
using geolens::IoError;

namespace {

/// A fresh empty folder per test, removed afterwards.
class ImageFileTest : public geolens::testing::ScratchFolderTest {
 protected:
  /// Names of the entries of the folder, sorted.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
};

/// A smooth image (JPEG compresses it well).
Image gradient(int width, int height, int channels) {
  Image image(width, height, channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c)
        image.at(x, y)[c] = uint8_t(40 + (x * 150) / width + (y * 50) / height + c * 10);
  return image;
}

double mean_abs_diff(const Image& a, const Image& b) {
  double sum = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) sum += std::abs(int(a.pixels[i]) - int(b.pixels[i]));
  return sum / double(a.pixels.size());
}

void write_bytes(const std::string& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

}  // namespace

TEST(ImageTest, ConstructorSizesAndFills) {
  const Image image(5, 3, 4, 17);
  EXPECT_EQ(image.width, 5);
  EXPECT_EQ(image.height, 3);
  EXPECT_EQ(image.channels, 4);
  ASSERT_EQ(image.pixels.size(), 5u * 3u * 4u);
  for (uint8_t v : image.pixels) EXPECT_EQ(v, 17);
  EXPECT_EQ(image.at(2, 1) - image.pixels.data(), (1 * 5 + 2) * 4);
}

TEST(ImageTest, ConstructorRejectsBadChannelsAndSizes) {
  EXPECT_THROW(Image(2, 2, 0), InvalidInput);
  EXPECT_THROW(Image(2, 2, 5), InvalidInput);
  EXPECT_THROW(Image(-1, 2, 3), InvalidInput);
}

TEST(ImageTest, WritablePathsAreDecidedByExtensionIgnoringCase) {
  EXPECT_TRUE(geolens::is_writable_image_path("a.png"));
  EXPECT_TRUE(geolens::is_writable_image_path("dir/a.PNG"));
  EXPECT_TRUE(geolens::is_writable_image_path("a.jpg"));
  EXPECT_TRUE(geolens::is_writable_image_path("a.JpEg"));
  EXPECT_FALSE(geolens::is_writable_image_path("a.bmp"));
  EXPECT_FALSE(geolens::is_writable_image_path("png"));
  EXPECT_FALSE(geolens::is_writable_image_path("a.png.txt"));
}

TEST_F(ImageFileTest, PngRoundTripIsLosslessForEveryChannelCount) {
  for (int channels = 1; channels <= 4; ++channels) {
    const Image image = geolens::test::pattern(37, 23, channels);
    const std::string file = path("image" + std::to_string(channels) + ".png");
    geolens::save_image(file, image);
    const Image loaded = geolens::load_image(file);
    EXPECT_EQ(loaded.width, image.width);
    EXPECT_EQ(loaded.height, image.height);
    EXPECT_EQ(loaded.channels, channels);
    EXPECT_EQ(loaded.pixels, image.pixels) << channels << " channels";
  }
  EXPECT_EQ(entries().size(), 4u);  // no temporary file left behind
}

TEST_F(ImageFileTest, UpperCaseExtensionsWork) {
  geolens::save_image(path("a.PNG"), geolens::test::pattern(8, 8, 3));
  geolens::save_image(path("b.JPEG"), gradient(8, 8, 3));
  EXPECT_EQ(geolens::load_image(path("a.PNG")).pixels, geolens::test::pattern(8, 8, 3).pixels);
  EXPECT_EQ(geolens::load_image(path("b.JPEG")).width, 8);
}

TEST_F(ImageFileTest, JpegRoundTripIsClose) {
  const Image image = gradient(64, 48, 3);
  geolens::save_image(path("a.jpg"), image, 95);
  const Image loaded = geolens::load_image(path("a.jpg"));
  ASSERT_EQ(loaded.width, 64);
  ASSERT_EQ(loaded.height, 48);
  ASSERT_EQ(loaded.channels, 3);
  EXPECT_LT(mean_abs_diff(loaded, image), 2.0);
}

TEST_F(ImageFileTest, JpegDropsAlphaAndStoresColour) {
  for (int channels = 1; channels <= 4; ++channels) {
    const Image image = gradient(32, 32, channels);
    geolens::save_image(path("a.jpeg"), image);
    const Image loaded = geolens::load_image(path("a.jpeg"));
    ASSERT_EQ(loaded.channels, 3);
    // Grey (+ alpha) reads back as three equal channels, RGB(A) as its colour channels.
    Image expected(32, 32, 3);
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x)
        for (int c = 0; c < 3; ++c) expected.at(x, y)[c] = image.at(x, y)[channels < 3 ? 0 : c];
    EXPECT_LT(mean_abs_diff(loaded, expected), 2.0) << channels << " channels";
  }
}

TEST_F(ImageFileTest, JpegQualityTradesSizeForError) {
  const Image image = geolens::test::pattern(64, 64, 3);
  geolens::save_image(path("low.jpg"), image, 10);
  geolens::save_image(path("high.jpg"), image, 100);
  EXPECT_LT(fs::file_size(path("low.jpg")), fs::file_size(path("high.jpg")));
  EXPECT_LT(mean_abs_diff(geolens::load_image(path("high.jpg")), image),
            mean_abs_diff(geolens::load_image(path("low.jpg")), image));
}

TEST_F(ImageFileTest, SaveReplacesAnExistingFile) {
  geolens::save_image(path("a.png"), Image(4, 4, 1, 10));
  geolens::save_image(path("a.png"), Image(6, 2, 1, 200));
  const Image loaded = geolens::load_image(path("a.png"));
  EXPECT_EQ(loaded.width, 6);
  EXPECT_EQ(loaded.pixels, Image(6, 2, 1, 200).pixels);
  EXPECT_EQ(entries(), std::vector<std::string>{"a.png"});
}

TEST_F(ImageFileTest, MissingFileThrowsInvalidInputNamingThePath) {
  const std::string file = path("missing.png");
  try {
    geolens::load_image(file);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("load_image: cannot read '" + file + "': ", 0), 0u) << message;
  }
}

TEST_F(ImageFileTest, CorruptFilesThrowInvalidInput) {
  write_bytes(path("garbage.png"), "this is not an image at all");
  EXPECT_THROW(geolens::load_image(path("garbage.png")), InvalidInput);
  write_bytes(path("empty.jpg"), "");
  EXPECT_THROW(geolens::load_image(path("empty.jpg")), InvalidInput);
  // A real PNG cut short.
  geolens::save_image(path("whole.png"), geolens::test::pattern(64, 64, 3));
  std::ifstream in(path("whole.png"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  write_bytes(path("cut.png"), bytes.substr(0, bytes.size() / 2));
  EXPECT_THROW(geolens::load_image(path("cut.png")), InvalidInput);
  EXPECT_THROW(geolens::load_image(dir_.string()), InvalidInput);  // a folder
}

TEST_F(ImageFileTest, UnknownExtensionThrowsAndWritesNothing) {
  EXPECT_THROW(geolens::save_image(path("a.bmp"), geolens::test::pattern(4, 4, 3)), InvalidInput);
  EXPECT_THROW(geolens::save_image(path("noextension"), geolens::test::pattern(4, 4, 3)),
               InvalidInput);
  EXPECT_TRUE(entries().empty());
}

TEST_F(ImageFileTest, MissingFolderThrowsAndWritesNothing) {
  EXPECT_THROW(geolens::save_image(path("nowhere/a.png"), geolens::test::pattern(4, 4, 3)),
               InvalidInput);
  EXPECT_TRUE(entries().empty());
}

TEST_F(ImageFileTest, InvalidImageOrQualityThrows) {
  Image broken(4, 4, 3);
  broken.pixels.pop_back();
  EXPECT_THROW(geolens::save_image(path("a.png"), broken), InvalidInput);
  EXPECT_THROW(geolens::save_image(path("a.png"), Image()), InvalidInput);
  EXPECT_THROW(geolens::save_image(path("a.jpg"), geolens::test::pattern(4, 4, 3), 0),
               InvalidInput);
  EXPECT_THROW(geolens::save_image(path("a.jpg"), geolens::test::pattern(4, 4, 3), 101),
               InvalidInput);
  EXPECT_TRUE(entries().empty());
}

TEST_F(ImageFileTest, FailedWriteThrowsIoErrorAndLeavesNoTemporary) {
  // The target is a non-empty folder: the final rename cannot replace it.
  fs::create_directories(dir_ / "taken.png" / "inside");
  EXPECT_THROW(geolens::save_image(path("taken.png"), geolens::test::pattern(4, 4, 3)), IoError);
  EXPECT_EQ(entries(), std::vector<std::string>{"taken.png"});
  EXPECT_TRUE(fs::is_directory(dir_ / "taken.png"));
}

namespace {

// A PNG written here from its specification (stored deflate blocks, CRC-32, Adler-32), so the
// decoder is tested on files no geolens encoder made: 16-bit samples, palettes, damaged streams.
uint32_t crc32(const std::string& bytes) {
  uint32_t c = 0xffffffffu;
  for (unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

std::string big_endian(uint32_t v) { return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; }

std::string chunk(const std::string& type, const std::string& data) {
  return big_endian(uint32_t(data.size())) + type + data + big_endian(crc32(type + data));
}

// A zlib stream of one stored block holding `raw`; `block_type` 3 makes it invalid (reserved).
std::string zlib_stored(const std::string& raw, int block_type = 0) {
  uint32_t a = 1, b = 0;
  for (unsigned char c : raw) a = (a + c) % 65521, b = (b + a) % 65521;
  const uint16_t n = uint16_t(raw.size());
  std::string out = "\x78\x01";
  out += char(1 | (block_type << 1));  // final block
  out += {char(n & 0xff), char(n >> 8), char(~n & 0xff), char((~n >> 8) & 0xff)};
  return out + raw + big_endian((b << 16) | a);
}

// A width x height PNG of `depth` bits and colour type `colour` whose scanlines (filter byte 0
// each) hold `samples` big-endian; extra chunks (PLTE, tRNS) before IDAT.
std::string png(int width, int height, int depth, int colour, const std::vector<int>& samples,
                const std::string& extra = "", int block_type = 0) {
  const int per_pixel = std::vector<int>{1, 0, 3, 1, 2, 0, 4}[size_t(colour)];
  std::string raw;
  size_t next = 0;
  for (int y = 0; y < height; ++y) {
    raw += '\0';
    for (int i = 0; i < width * per_pixel; ++i) {
      const int v = samples[next++];
      if (depth == 16) raw += char(v >> 8);
      raw += char(v & 0xff);
    }
  }
  const std::string ihdr = big_endian(uint32_t(width)) + big_endian(uint32_t(height)) +
                           char(depth) + char(colour) + std::string(3, '\0');
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + extra +
         chunk("IDAT", zlib_stored(raw, block_type)) + chunk("IEND", "");
}

}  // namespace

TEST_F(ImageFileTest, SixteenBitPngIsReadAtItsDepth) {
  // A 16-bit grey mask of values 0 and 1 - 255: rounded to 8 bits it would be all 0 and 1.
  write_bytes(path("mask16.png"), png(4, 1, 16, 0, {0, 1, 255, 65535}));
  const Image mask = geolens::load_mask(path("mask16.png"));
  ASSERT_EQ(mask.channels, 1);
  EXPECT_EQ(mask.pixels, (std::vector<uint8_t>{0, 255, 255, 255}));
  const Image picture = geolens::load_image(path("mask16.png"));
  EXPECT_EQ(picture.pixels, (std::vector<uint8_t>{0, 0, 1, 255}));  // v * 255 / 65535, rounded
  // 16-bit RGB keeps its channels, each rounded.
  write_bytes(path("rgb16.png"), png(1, 1, 16, 2, {65535, 32896, 257}));
  EXPECT_EQ(geolens::load_image(path("rgb16.png")).pixels, (std::vector<uint8_t>{255, 128, 1}));
}

TEST_F(ImageFileTest, PaletteWithTransparencyBecomesRgba) {
  const std::string plte = chunk("PLTE", std::string("\x10\x20\x30\xf0\xe0\xd0", 6));
  const std::string trns = chunk("tRNS", std::string("\x00", 1));  // entry 0 transparent
  write_bytes(path("palette.png"), png(2, 1, 8, 3, {0, 1}, plte + trns));
  const Image image = geolens::load_image(path("palette.png"));
  ASSERT_EQ(image.channels, 4);
  EXPECT_EQ(image.pixels, (std::vector<uint8_t>{0x10, 0x20, 0x30, 0, 0xf0, 0xe0, 0xd0, 255}));
}

// max_pixels bounds what an image may decode to, named in the refusal; a picture of exactly that
// many pixels is read, PNG and JPEG alike, and the limit must be at least 1.
TEST_F(ImageFileTest, MaxPixelsIsALimitThatNamesItself) {
  for (const std::string name : {"limit.png", "limit.jpg"}) {
    geolens::save_image(path(name), gradient(40, 30, 3));
    EXPECT_EQ(geolens::load_image(path(name), 1200).width, 40) << name;
    const std::string refused =
        geolens::test::refusal([&] { geolens::load_image(path(name), 1199); });
    EXPECT_NE(refused.find("40 x 30 pixels is more than the 1199 read (max_pixels"),
              std::string::npos)
        << refused;
    EXPECT_NE(
        geolens::test::refusal([&] { geolens::load_mask(path(name), 1199); }).find("max_pixels"),
        std::string::npos);
    EXPECT_NE(geolens::test::refusal([&] {
                geolens::load_image(path(name), 0);
              }).find("max_pixels must be >= 1"),
              std::string::npos);
  }
}

TEST_F(ImageFileTest, DamagedFilesAreRefusedWithOneLineNamingTheFileAndTheFault) {
  auto message = [&](const std::string& file) {
    try {
      geolens::load_image(path(file));
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // A deflate block of the reserved type 3 (stb answered with an exception from std::string).
  write_bytes(path("reserved.png"), png(2, 2, 8, 0, {1, 2, 3, 4}, "", 3));
  const std::string reserved = message("reserved.png");
  EXPECT_EQ(reserved.rfind("load_image: cannot read '" + path("reserved.png") + "': PNG", 0), 0u)
      << reserved;
  EXPECT_EQ(reserved.find('\n'), std::string::npos);
  // A JPEG cut short is refused, not completed with grey.
  geolens::save_image(path("whole.jpg"), gradient(64, 64, 3));
  std::ifstream in(path("whole.jpg"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  write_bytes(path("cut.jpg"), bytes.substr(0, bytes.size() * 2 / 3));
  EXPECT_NE(message("cut.jpg").find("JPEG"), std::string::npos) << message("cut.jpg");
  // A header claiming 20000 x 20000 pixels is refused before anything is allocated.
  const std::string huge =
      big_endian(20000) + big_endian(20000) + char(8) + char(2) + std::string(3, '\0');
  write_bytes(path("huge.png"), std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", huge) +
                                    chunk("IDAT", zlib_stored("")) + chunk("IEND", ""));
  EXPECT_NE(message("huge.png")
                .find("20000 x 20000 pixels is more than the 268435456 read "
                      "(max_pixels; --max-pixels raises it)"),
            std::string::npos)
      << message("huge.png");
  // 16384 x 16384 pixels (2^28, allowed) at 16 bits RGBA is decoded a row at a time into 8 bits:
  // a file whose data is missing is refused at its first row, nothing of its size allocated.
  const std::string deep =
      big_endian(16384) + big_endian(16384) + char(16) + char(6) + std::string(3, '\0');
  write_bytes(path("deep.png"), std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", deep) +
                                    chunk("IDAT", zlib_stored("")) + chunk("IEND", ""));
  EXPECT_NE(message("deep.png").find("PNG data"), std::string::npos) << message("deep.png");
  // A wrong checksum of the image data (read after its last row) is refused.
  geolens::save_image(path("whole.png"), gradient(32, 32, 3));
  std::ifstream png(path("whole.png"), std::ios::binary);
  std::string damaged((std::istreambuf_iterator<char>(png)), std::istreambuf_iterator<char>());
  const size_t idat = damaged.find("IDAT");
  size_t length = 0;
  for (size_t k = idat - 4; k < idat; ++k) length = length << 8 | uint8_t(damaged[k]);
  damaged[idat + 4 + length] = char(damaged[idat + 4 + length] ^ 0xff);  // its checksum's byte
  write_bytes(path("damaged.png"), damaged);
  EXPECT_NE(message("damaged.png").find("checksum"), std::string::npos) << message("damaged.png");
  // Neither format: said so.
  write_bytes(path("text.png"), "hello");
  EXPECT_NE(message("text.png").find("not a PNG or JPEG file"), std::string::npos);
}
