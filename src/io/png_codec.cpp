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

}  // namespace

bool is_png(const std::vector<uint8_t>& bytes) {
  static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  return bytes.size() >= 8 && std::equal(kSignature, kSignature + 8, bytes.begin());
}

Image decode_png(const std::vector<uint8_t>& bytes, Depth depth) {
  Context ctx(spng_ctx_new(0), &spng_ctx_free);
  if (!ctx) throw CodecError("out of memory");
  check(spng_set_image_limits(ctx.get(), kMaxSide, kMaxSide), "PNG");
  check(spng_set_chunk_limits(ctx.get(), kMaxChunk, kMaxChunk), "PNG");
  check(spng_set_png_buffer(ctx.get(), bytes.data(), bytes.size()), "PNG");
  spng_ihdr ihdr{};
  check(spng_get_ihdr(ctx.get(), &ihdr), "PNG header");
  if (uint64_t(ihdr.width) * ihdr.height > kMaxPixels)
    throw CodecError("PNG: " + std::to_string(ihdr.width) + " x " + std::to_string(ihdr.height) +
                     " pixels is more than geolens reads (2^28)");
  spng_trns trns{};
  const bool has_trns = spng_get_trns(ctx.get(), &trns) == 0;
  int channels = 4;
  switch (ihdr.color_type) {
    case SPNG_COLOR_TYPE_GRAYSCALE:
      channels = has_trns ? 2 : 1;
      break;
    case SPNG_COLOR_TYPE_GRAYSCALE_ALPHA:
      channels = 2;
      break;
    case SPNG_COLOR_TYPE_TRUECOLOR:
    case SPNG_COLOR_TYPE_INDEXED:
      channels = has_trns ? 4 : 3;
      break;
    default:
      channels = 4;
  }
  // Decoded as RGBA at the file's depth (8 or 16 bits), then reduced to its channels.
  const bool deep = ihdr.bit_depth == 16;
  const int format = deep ? SPNG_FMT_RGBA16 : SPNG_FMT_RGBA8;
  size_t size = 0;
  check(spng_decoded_image_size(ctx.get(), format, &size), "PNG");
  // 2^28 pixels at 16 bits a sample would be 2 GiB of RGBA before the image is made.
  if (size > kMaxDecodedBytes)
    throw CodecError("PNG: " + std::to_string(ihdr.width) + " x " + std::to_string(ihdr.height) +
                     " pixels at " + std::to_string(int(ihdr.bit_depth)) + " bits decode to " +
                     std::to_string(size) + " bytes, more than geolens reads (2^30)");
  std::vector<uint8_t> rgba(size);
  check(spng_decode_image(ctx.get(), rgba.data(), size, format, SPNG_DECODE_TRNS), "PNG data");
  Image image(int(ihdr.width), int(ihdr.height), channels);
  const size_t n = size_t(ihdr.width) * ihdr.height;
  // RGBA -> the kept channels: grey takes R, grey + alpha R and A.
  const int pick[4][4] = {{0}, {0, 3}, {0, 1, 2}, {0, 1, 2, 3}};
  for (size_t p = 0; p < n; ++p) {
    for (int c = 0; c < channels; ++c) {
      const int k = pick[channels - 1][c];
      uint8_t value;
      if (deep) {
        uint16_t v;
        std::memcpy(&v, rgba.data() + (4 * p + size_t(k)) * 2, 2);
        value = depth == Depth::kNonZero && c == 0 ? uint8_t(v ? 255 : 0)
                                                   : uint8_t((uint32_t(v) * 255 + 32767) / 65535);
      } else {
        value = rgba[4 * p + size_t(k)];
        if (depth == Depth::kNonZero && c == 0) value = value ? 255 : 0;
      }
      image.pixels[p * size_t(channels) + size_t(c)] = value;
    }
  }
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
