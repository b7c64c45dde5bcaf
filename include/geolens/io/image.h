#pragma once
// 8-bit images in memory, PNG and JPEG files in and out (the codecs: src/io/*_codec.cpp).

#include <cstdint>
#include <string>
#include <vector>

namespace geolens {

/// An 8-bit image, row-major, channels interleaved, top row first.
struct Image {
  int width = 0;                ///< pixels
  int height = 0;               ///< pixels
  int channels = 0;             ///< 1 (grey), 2 (grey+alpha), 3 (RGB) or 4 (RGBA)
  std::vector<uint8_t> pixels;  ///< width * height * channels bytes

  Image() = default;
  /// A width x height image with `channels` channels, every byte set to `fill`.
  Image(int width, int height, int channels, uint8_t fill = 0);
  /// The first of the `channels` bytes of pixel (x, y) (x from the left, y from the top); not
  /// bounds-checked: x in [0, width), y in [0, height).
  ///@{
  uint8_t* at(int x, int y) { return pixels.data() + (size_t(y) * width + x) * channels; }
  const uint8_t* at(int x, int y) const {
    return pixels.data() + (size_t(y) * width + x) * channels;
  }
  ///@}
};

/// The most pixels load_image decodes unless told otherwise: 2^28 (16384 x 16384; 1 GiB as RGBA).
constexpr uint64_t kMaxImagePixels = uint64_t(1) << 28;

/// Reads a PNG (libspng: any colour type and depth; palette to RGB(A), transparency to alpha) or
/// a JPEG (libjpeg-turbo: grey or RGB), recognized by content, not by extension. 16-bit samples
/// are rounded to 8 bits. Throws InvalidInput naming the path and what is wrong when the file is
/// missing, unreadable, corrupt (a damaged JPEG is refused, not decoded with made-up pixels) or
/// larger than `max_pixels` (>= 1; the message names the limit, max_pixels) or 2^16 on a PNG's
/// side, refused from its header before any allocation.
Image load_image(const std::string& path, uint64_t max_pixels = kMaxImagePixels);

/// Reads a mask: like load_image, but the first channel is 255 wherever the file's sample is
/// non-zero at its own depth and 0 elsewhere (so a 16-bit mask of values 1 - 255 is not empty).
Image load_mask(const std::string& path, uint64_t max_pixels = kMaxImagePixels);

/// Writes `image` as PNG (libspng, a fast compression setting) or JPEG (libjpeg-turbo), chosen by
/// the extension (.png, .jpg, .jpeg; case-insensitive), through write_file (file_io.h), so
/// `path` is never left partial. Throws InvalidInput for an unknown extension or a missing folder,
/// IoError when writing fails. `jpeg_quality` in [1, 100]. JPEG has no alpha: it is dropped, and
/// the file is always 3-channel colour (a grey image reads back as 3 equal channels).
void save_image(const std::string& path, const Image& image, int jpeg_quality = 92);

/// True when the extension of `path` is one save_image can write.
bool is_writable_image_path(const std::string& path);

}  // namespace geolens
