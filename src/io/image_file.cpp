// PNG and JPEG files in and out (the codecs: src/io/*_codec.cpp); the Image type is image.cpp.

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <system_error>

#include "core/limits.h"
#include "geolens/core/errors.h"
#include "geolens/io/file_io.h"
#include "geolens/io/image.h"
#include "io/codecs.h"

namespace geolens {

namespace fs = std::filesystem;

namespace {

enum class Format { kPng, kJpeg, kUnknown };

Format format_of(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".png") return Format::kPng;
  if (ext == ".jpg" || ext == ".jpeg") return Format::kJpeg;
  return Format::kUnknown;
}

// The whole file, or the reason it cannot be read.
std::vector<uint8_t> read_bytes(const std::string& path, std::string& reason) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    // Read whole, a device never ends (/dev/zero) and a FIFO may never open.
    reason = std::filesystem::is_directory(status)
                 ? "it is a directory"
                 : "it is not a regular file (a device or a FIFO)";
    return {};
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                       &std::fclose);
  std::vector<uint8_t> bytes;
  if (!file) {
    reason = std::strerror(errno);
    return bytes;
  }
  uint8_t chunk[1 << 16];
  for (size_t n; (n = std::fread(chunk, 1, sizeof chunk, file.get())) > 0;)
    bytes.insert(bytes.end(), chunk, chunk + n);
  if (std::ferror(file.get())) reason = std::strerror(errno);
  return bytes;
}

Image decode(const std::string& path, codecs::Depth depth, uint64_t max_pixels,
             const char* function) {
  require(max_pixels >= 1, function, "max_pixels must be >= 1, got 0");
  std::string reason;
  const std::vector<uint8_t> bytes = read_bytes(path, reason);
  auto fail = [&](const std::string& why) {
    return InvalidInput(std::string(function) + ": cannot read '" + path + "': " + why);
  };
  if (!reason.empty()) throw fail(reason);
  try {
    if (codecs::is_png(bytes)) return codecs::decode_png(bytes, depth, max_pixels);
    if (codecs::is_jpeg(bytes)) return codecs::decode_jpeg(bytes, depth, max_pixels);
  } catch (const codecs::CodecError& e) {
    throw fail(e.what());
  }
  throw fail(bytes.empty() ? "the file is empty" : "not a PNG or JPEG file");
}

}  // namespace

Image load_image(const std::string& path, uint64_t max_pixels) {
  return decode(path, codecs::Depth::kRound, max_pixels, "load_image");
}

Image load_mask(const std::string& path, uint64_t max_pixels) {
  return decode(path, codecs::Depth::kNonZero, max_pixels, "load_mask");
}

namespace codecs {

std::string limit_message(uint64_t width, uint64_t height, uint64_t max_pixels) {
  return std::to_string(width) + " x " + std::to_string(height) + " pixels is " +
         over_limit(max_pixels, "max_pixels");
}

}  // namespace codecs

void save_image(const std::string& path, const Image& image, int jpeg_quality) {
  const Format format = format_of(path);
  require(format != Format::kUnknown, "save_image",
          "unknown extension in '" + path + "' (expected .png, .jpg or .jpeg)");
  require(image.width > 0 && image.height > 0 && image.channels >= 1 && image.channels <= 4,
          "save_image",
          "image must be non-empty with 1 to 4 channels, got " + std::to_string(image.width) +
              " x " + std::to_string(image.height) + " x " + std::to_string(image.channels));
  require(
      image.pixels.size() == size_t(image.width) * size_t(image.height) * size_t(image.channels),
      "save_image",
      "image has " + std::to_string(image.pixels.size()) +
          " bytes, expected width * height * "
          "channels");
  require(jpeg_quality >= 1 && jpeg_quality <= 100, "save_image",
          "jpeg_quality must be in [1, 100], got " + std::to_string(jpeg_quality));
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  require(parent.empty() || fs::is_directory(parent, ec), "save_image",
          "folder '" + parent.string() + "' of '" + path + "' does not exist");

  std::vector<uint8_t> bytes;
  try {
    bytes = format == Format::kPng ? codecs::encode_png(image)
                                   : codecs::encode_jpeg(image, jpeg_quality);
  } catch (const codecs::CodecError& e) {
    throw IoError("save_image: cannot encode '" + path + "': " + e.what());
  }
  write_file(path, bytes.data(), bytes.size());
}

bool is_writable_image_path(const std::string& path) { return format_of(path) != Format::kUnknown; }

}  // namespace geolens
