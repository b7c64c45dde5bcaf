#pragma once
// Private: the PNG (libspng) and JPEG (libjpeg-turbo) codecs behind load_image and save_image.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
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

/// The largest image decoded: 2^28 pixels (16384 x 16384; 1 GiB as RGBA), so a header that
/// claims more is refused before any allocation.
constexpr uint64_t kMaxPixels = uint64_t(1) << 28;

bool is_png(const std::vector<uint8_t>& bytes);
bool is_jpeg(const std::vector<uint8_t>& bytes);

/// Decodes a whole PNG file: 1, 2, 3 or 4 channels as stored (palette -> RGB or RGBA, tRNS ->
/// alpha), 16-bit samples per `depth`. Throws CodecError naming what is wrong.
Image decode_png(const std::vector<uint8_t>& bytes, Depth depth);
/// Encodes 8-bit PNG at a fast compression setting (zlib level 2, Sub and Up filters).
std::vector<uint8_t> encode_png(const Image& image);

/// Decodes a baseline or progressive JPEG to grey (1 channel) or RGB (3), `depth` applied to the
/// first channel. Any corrupt-data warning of the decoder is an error. Throws CodecError.
Image decode_jpeg(const std::vector<uint8_t>& bytes, Depth depth);
/// Encodes RGB JPEG (grey repeated, alpha dropped) at `quality` in [1, 100].
std::vector<uint8_t> encode_jpeg(const Image& image, int quality);

}  // namespace geolens::codecs
