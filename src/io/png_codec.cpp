#include <spng.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include "io/codecs.h"

namespace geolens::codecs {

namespace {

using Context = std::unique_ptr<spng_ctx, void (*)(spng_ctx*)>;

void check(int error, const char* what) {
  if (error) throw CodecError(std::string(what) + ": " + spng_strerror(error));
}

// Images above this many pixels or with a chunk above this size are refused before decoding.
constexpr uint32_t kMaxSide = 1u << 16;
constexpr size_t kMaxChunk = size_t(64) << 20;

/// Refuses a PNG whose header claims more pixels than geolens reads, in geolens's words: the
/// size from the header's own bytes (big-endian width and height after the signature and the
/// IHDR chunk's length and type).
void check_claimed_size(const std::vector<uint8_t>& bytes, uint64_t max_pixels) {
  if (bytes.size() < 24) return;
  auto word = [&](size_t at) {
    return uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 |
           uint32_t(bytes[at + 2]) << 8 | uint32_t(bytes[at + 3]);
  };
  const uint32_t width = word(16), height = word(20);
  if (width > kMaxSide || height > kMaxSide)
    throw CodecError("PNG: " + std::to_string(width) + " x " + std::to_string(height) +
                     " pixels: a side is more than geolens reads (2^16)");
  if (uint64_t(width) * height > max_pixels)
    throw CodecError("PNG: " + limit_message(width, height, max_pixels));
}

/// A decoder of `bytes` (which it keeps pointing to) with geolens's limits.
Context png_decoder(const std::vector<uint8_t>& bytes) {
  Context ctx(spng_ctx_new(0), &spng_ctx_free);
  if (!ctx) throw CodecError("out of memory");
  check(spng_set_image_limits(ctx.get(), kMaxSide, kMaxSide), "PNG");
  check(spng_set_chunk_limits(ctx.get(), kMaxChunk, kMaxChunk), "PNG");
  // A damaged chunk is refused, not decoded into made-up pixels.
  check(spng_set_crc_action(ctx.get(), SPNG_CRC_ERROR, SPNG_CRC_ERROR), "PNG");
  check(spng_set_png_buffer(ctx.get(), bytes.data(), bytes.size()), "PNG");
  return ctx;
}

/// The channels kept of a PNG of colour type `color_type`: grey 1, grey and alpha 2, RGB 3,
/// RGBA 4; a transparency chunk (`has_trns`) adds alpha.
int kept_channels(uint8_t color_type, bool has_trns) {
  switch (color_type) {
    case SPNG_COLOR_TYPE_GRAYSCALE:
      return has_trns ? 2 : 1;
    case SPNG_COLOR_TYPE_GRAYSCALE_ALPHA:
      return 2;
    case SPNG_COLOR_TYPE_TRUECOLOR:
    case SPNG_COLOR_TYPE_INDEXED:
      return has_trns ? 4 : 3;
    default:
      return 4;
  }
}

/// Appends a decoded RGBA row of `width` pixels (16 bits a value if `deep`, else 8) to `pixels`,
/// reduced to its `channels` and to 8 bits; Depth::kNonZero makes the first channel 0 or 255.
void append_row(const std::vector<uint8_t>& row, size_t width, bool deep, int channels, Depth depth,
                std::vector<uint8_t>& pixels) {
  // RGBA -> the kept channels: grey takes R, grey + alpha R and A.
  static constexpr int pick[4][4] = {{0}, {0, 3}, {0, 1, 2}, {0, 1, 2, 3}};
  for (size_t p = 0; p < width; ++p) {
    for (int c = 0; c < channels; ++c) {
      const int k = pick[channels - 1][c];
      uint8_t value;
      if (deep) {
        uint16_t v;
        std::memcpy(&v, row.data() + (4 * p + size_t(k)) * 2, 2);
        value = depth == Depth::kNonZero && c == 0 ? uint8_t(v ? 255 : 0)
                                                   : uint8_t((uint32_t(v) * 255 + 32767) / 65535);
      } else {
        value = row[4 * p + size_t(k)];
        if (depth == Depth::kNonZero && c == 0) value = value ? 255 : 0;
      }
      pixels.push_back(value);
    }
  }
}

}  // namespace

bool is_png(const std::vector<uint8_t>& bytes) {
  static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  return bytes.size() >= 8 && std::equal(kSignature, kSignature + 8, bytes.begin());
}

Image decode_png(const std::vector<uint8_t>& bytes, Depth depth, uint64_t max_pixels) {
  check_claimed_size(bytes, max_pixels);
  const Context ctx = png_decoder(bytes);
  spng_ihdr ihdr{};
  check(spng_get_ihdr(ctx.get(), &ihdr), "PNG header");
  spng_trns trns{};
  const bool has_trns = spng_get_trns(ctx.get(), &trns) == 0;
  const int channels = kept_channels(ihdr.color_type, has_trns);
  // Decoded a row at a time as RGBA at the file's depth (8 or 16 bits), each row reduced to the
  // file's channels as it comes: the only image held is the result, whose pages are touched
  // only as rows arrive (a 120-byte file claiming 16384 x 16384 RGBA took 1 GiB, zero-filled,
  // before its data was found missing).
  const bool deep = ihdr.bit_depth == 16;
  const int format = deep ? SPNG_FMT_RGBA16 : SPNG_FMT_RGBA8;
  check(
      spng_decode_image(ctx.get(), nullptr, 0, format, SPNG_DECODE_TRNS | SPNG_DECODE_PROGRESSIVE),
      "PNG data");
  const size_t width = ihdr.width, row_bytes = width * 4 * (deep ? 2 : 1);
  std::vector<uint8_t> row(row_bytes);
  Image image;
  image.width = int(ihdr.width);
  image.height = int(ihdr.height);
  image.channels = channels;
  image.pixels.reserve(width * ihdr.height * size_t(channels));
  for (uint32_t y = 0; y < ihdr.height; ++y) {
    const int error = spng_decode_row(ctx.get(), row.data(), row_bytes);
    if (error != 0 && !(error == SPNG_EOI && y + 1 == ihdr.height)) check(error, "PNG data");
    append_row(row, width, deep, channels, depth, image.pixels);
  }
  // The chunks after the last row, through IEND, so the image data's own checksum is read too
  // (a damaged byte can still inflate, to made-up pixels).
  check(spng_decode_chunks(ctx.get()), "PNG data");
  return image;
}

std::vector<uint8_t> encode_png(const Image& image) {
  Context ctx(spng_ctx_new(SPNG_CTX_ENCODER), &spng_ctx_free);
  if (!ctx) throw CodecError("out of memory");
  static const uint8_t kColour[5] = {0, SPNG_COLOR_TYPE_GRAYSCALE, SPNG_COLOR_TYPE_GRAYSCALE_ALPHA,
                                     SPNG_COLOR_TYPE_TRUECOLOR, SPNG_COLOR_TYPE_TRUECOLOR_ALPHA};
  spng_ihdr ihdr{};
  ihdr.width = uint32_t(image.width);
  ihdr.height = uint32_t(image.height);
  ihdr.bit_depth = 8;
  ihdr.color_type = kColour[image.channels];
  check(spng_set_ihdr(ctx.get(), &ihdr), "PNG encoder");
  check(spng_set_option(ctx.get(), SPNG_ENCODE_TO_BUFFER, 1), "PNG encoder");
  // Level 2 and two cheap filters: a 1024 x 1024 photo in tens of milliseconds, a few percent
  // larger than zlib's default (bench/README.md).
  check(spng_set_option(ctx.get(), SPNG_IMG_COMPRESSION_LEVEL, 2), "PNG encoder");
  check(spng_set_option(ctx.get(), SPNG_FILTER_CHOICE,
                        SPNG_FILTER_CHOICE_SUB | SPNG_FILTER_CHOICE_UP),
        "PNG encoder");
  check(spng_encode_image(ctx.get(), image.pixels.data(), image.pixels.size(), SPNG_FMT_PNG,
                          SPNG_ENCODE_FINALIZE),
        "PNG encoder");
  size_t size = 0;
  int error = 0;
  std::unique_ptr<uint8_t, void (*)(void*)> buffer(
      static_cast<uint8_t*>(spng_get_png_buffer(ctx.get(), &size, &error)), &std::free);
  check(error, "PNG encoder");
  return std::vector<uint8_t>(buffer.get(), buffer.get() + size);
}

}  // namespace geolens::codecs
