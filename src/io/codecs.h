#pragma once
// Private: the PNG (libspng) and JPEG (libjpeg-turbo) codecs behind load_image and save_image.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "geolens/io/image.h"

namespace geolens::codecs {

/// What is wrong with a file or an encode, in one line (load_image and save_image add the path).
struct CodecError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// How samples deeper than 8 bits become bytes: rounded to the nearest of 256 levels (pictures),
/// or 255 wherever the first channel is non-zero and 0 elsewhere (masks, at the file's depth).
enum class Depth { kRound, kNonZero };

bool is_png(const std::vector<uint8_t>& bytes);
bool is_jpeg(const std::vector<uint8_t>& bytes);

/// Decodes a whole PNG file: 1, 2, 3 or 4 channels as stored (palette -> RGB or RGBA, tRNS ->
/// alpha), 16-bit samples per `depth`. Throws CodecError naming what is wrong, and for a header
/// that claims more than `max_pixels` before any allocation (limit_message).
Image decode_png(const std::vector<uint8_t>& bytes, Depth depth, uint64_t max_pixels);
/// Encodes 8-bit PNG at a fast compression setting (zlib level 2, Sub and Up filters).
std::vector<uint8_t> encode_png(const Image& image);

/// Decodes a baseline or progressive JPEG to grey (1 channel) or RGB (3), `depth` applied to the
/// first channel. Any corrupt-data warning of the decoder is an error. Throws CodecError, as
/// decode_png for more than `max_pixels`.
Image decode_jpeg(const std::vector<uint8_t>& bytes, Depth depth, uint64_t max_pixels);

/// What a codec says of a `width` x `height` picture over `max_pixels`, naming the limit.
std::string limit_message(uint64_t width, uint64_t height, uint64_t max_pixels);
/// Encodes RGB JPEG (grey repeated, alpha dropped) at `quality` in [1, 100].
std::vector<uint8_t> encode_jpeg(const Image& image, int quality);

}  // namespace geolens::codecs
