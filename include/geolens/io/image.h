#pragma once
// 8-bit images in memory, PNG and JPEG files in and out.

#include <cstdint>
#include <string>
#include <vector>

namespace geolens {

/// An 8-bit image, row-major, channels interleaved, top row first.
struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;             ///< 1 (grey), 2 (grey+alpha), 3 (RGB) or 4 (RGBA)
  std::vector<uint8_t> pixels;  ///< width * height * channels bytes

  Image() = default;
  /// A width x height image with `channels` channels, every byte set to `fill`.
  Image(int width, int height, int channels, uint8_t fill = 0);
  uint8_t* at(int x, int y) { return pixels.data() + (size_t(y) * width + x) * channels; }
  const uint8_t* at(int x, int y) const {
    return pixels.data() + (size_t(y) * width + x) * channels;
  }
};

/// Reads a PNG or JPEG file (any format stb_image decodes). Throws InvalidInput naming the path
/// and the decoder's reason when the file is missing, unreadable or corrupt.
Image load_image(const std::string& path);

/// Writes `image` as PNG or JPEG, chosen by the extension (.png, .jpg, .jpeg; case-insensitive).
/// Writes to a temporary file in the same folder and renames it into place, so `path` is never
/// left partial. Throws InvalidInput for an unknown extension or a missing folder, IoError when
/// writing fails. `jpeg_quality` in [1, 100]. JPEG has no alpha: it is dropped, and the file is
/// always 3-channel colour (a grey image reads back as 3 equal channels).
void save_image(const std::string& path, const Image& image, int jpeg_quality = 92);

/// True when the extension of `path` is one save_image can write.
bool is_writable_image_path(const std::string& path);

}  // namespace geolens
