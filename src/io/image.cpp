#include "geolens/io/image.h"

#include <stb_image.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <system_error>

#include "geolens/core/errors.h"

namespace geolens {

namespace fs = std::filesystem;

Image::Image(int width, int height, int channels, uint8_t fill)
    : width(width), height(height), channels(channels) {
  require(
      width >= 0 && height >= 0, "Image",
      "size must be non-negative, got " + std::to_string(width) + " x " + std::to_string(height));
  require(channels >= 1 && channels <= 4, "Image",
          "channels must be in [1, 4], got " + std::to_string(channels));
  pixels.assign(size_t(width) * size_t(height) * size_t(channels), fill);
}

namespace {

enum class Format { kPng, kJpeg, kUnknown };

Format format_of(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".png") return Format::kPng;
  if (ext == ".jpg" || ext == ".jpeg") return Format::kJpeg;
  return Format::kUnknown;
}

/// Encodes `image` in memory, so that writing the file can be checked byte for byte.
std::vector<uint8_t> encode(const Image& image, Format format, int jpeg_quality) {
  std::vector<uint8_t> bytes;
  auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    const auto* begin = static_cast<const uint8_t*>(data);
    out->insert(out->end(), begin, begin + size);
  };
  int ok = 0;
  if (format == Format::kPng) {
    ok = stbi_write_png_to_func(append, &bytes, image.width, image.height, image.channels,
                                image.pixels.data(), image.width * image.channels);
  } else {
    // JPEG has no alpha: the encoder reads grey or RGB and skips the alpha byte.
    ok = stbi_write_jpg_to_func(append, &bytes, image.width, image.height, image.channels,
                                image.pixels.data(), jpeg_quality);
  }
  if (!ok) throw IoError("save_image: the encoder failed");
  return bytes;
}

/// Writes `bytes` to `path`; returns an empty string on success, else the reason.
std::string write_file(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return std::strerror(errno);
  std::string reason;
  if (std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size())
    reason = std::strerror(errno);
  if (std::fclose(file) != 0 && reason.empty()) reason = std::strerror(errno);
  return reason;
}

}  // namespace

Image load_image(const std::string& path) {
  auto fail = [&](const std::string& reason) {
    return InvalidInput("load_image: cannot read '" + path + "': " + reason);
  };
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                       &std::fclose);
  if (!file) throw fail(std::strerror(errno));
  int width = 0, height = 0, channels = 0;
  std::unique_ptr<uint8_t, void (*)(void*)> data(
      stbi_load_from_file(file.get(), &width, &height, &channels, 0), &stbi_image_free);
  if (!data) throw fail(stbi_failure_reason());
  Image image(width, height, channels);
  std::memcpy(image.pixels.data(), data.get(), image.pixels.size());
  return image;
}

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

  const std::vector<uint8_t> bytes = encode(image, format, jpeg_quality);
  // Unique per process and per call, so concurrent saves of the same path do not collide.
  static std::atomic<unsigned> counter{0};
  const std::string temp =
      path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  std::string reason = write_file(temp, bytes);
  if (reason.empty()) {
    fs::rename(temp, path, ec);
    if (ec) reason = ec.message();
  }
  if (!reason.empty()) {
    fs::remove(temp, ec);
    throw IoError("save_image: cannot write '" + path + "': " + reason);
  }
}

bool is_writable_image_path(const std::string& path) { return format_of(path) != Format::kUnknown; }

}  // namespace geolens
