#include <csetjmp>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

// After <cstdio>: jpeglib.h uses size_t and FILE without including their headers.
#include <jpeglib.h>

#include "io/codecs.h"

namespace geolens::codecs {

namespace {

// libjpeg reports errors through a callback that must not return: it jumps back to the call,
// with the decoder's message. Corrupt-data warnings jump too, so a damaged file is refused
// instead of decoded with made-up pixels.
struct ErrorManager {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

void error_exit(j_common_ptr info) {
  auto* errors = reinterpret_cast<ErrorManager*>(info->err);
  info->err->format_message(info, errors->message);
  std::longjmp(errors->jump, 1);
}

void emit_message(j_common_ptr info, int level) {
  if (level < 0) error_exit(info);  // a warning: corrupt data
}

void install(ErrorManager& errors, j_common_ptr info) {
  info->err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = &error_exit;
  errors.manager.emit_message = &emit_message;
  errors.message[0] = '\0';
}

}  // namespace

bool is_jpeg(const std::vector<uint8_t>& bytes) {
  return bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff;
}

// The libjpeg objects live outside the setjmp frame and no C++ object with a destructor is
// created between setjmp and the last libjpeg call, so the jump skips no destructor.
Image decode_jpeg(const std::vector<uint8_t>& bytes, Depth depth, uint64_t max_pixels) {
  // A size over the limit, kept for the message made after the jump.
  volatile uint64_t over_width = 0, over_height = 0;
  jpeg_decompress_struct info{};
  ErrorManager errors;
  install(errors, reinterpret_cast<j_common_ptr>(&info));
  // On the heap: the pointer does not change after setjmp, so it is valid after the jump.
  const auto image = std::make_unique<Image>();
  if (setjmp(errors.jump)) {
    jpeg_destroy_decompress(&info);
    if (over_width > 0)
      throw CodecError("JPEG: " + limit_message(over_width, over_height, max_pixels));
    throw CodecError(std::string("JPEG: ") + errors.message);
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  if (info.jpeg_color_space == JCS_CMYK || info.jpeg_color_space == JCS_YCCK) {
    std::snprintf(errors.message, sizeof errors.message, "CMYK JPEG is not supported");
    std::longjmp(errors.jump, 1);
  }
  if (uint64_t(info.image_width) * info.image_height > max_pixels) {
    over_width = info.image_width;
    over_height = info.image_height;
    std::longjmp(errors.jump, 1);
  }
  info.out_color_space = info.num_components == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_start_decompress(&info);
  Image& out = *image;
  out.width = int(info.output_width);
  out.height = int(info.output_height);
  out.channels = int(info.output_components);
  out.pixels.resize(size_t(out.width) * size_t(out.height) * size_t(out.channels));
  while (info.output_scanline < info.output_height) {
    JSAMPROW row =
        out.pixels.data() + size_t(info.output_scanline) * size_t(out.width) * size_t(out.channels);
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  if (depth == Depth::kNonZero)
    for (size_t p = 0; p < out.pixels.size(); p += size_t(out.channels))
      out.pixels[p] = out.pixels[p] ? 255 : 0;
  return std::move(out);
}

std::vector<uint8_t> encode_jpeg(const Image& image, int quality) {
  // RGB rows: grey repeated, alpha dropped.
  const int c = image.channels;
  std::vector<uint8_t> rgb(size_t(image.width) * size_t(image.height) * 3);
  for (size_t p = 0, n = size_t(image.width) * size_t(image.height); p < n; ++p) {
    const uint8_t* in = image.pixels.data() + p * size_t(c);
    for (int k = 0; k < 3; ++k) rgb[3 * p + size_t(k)] = in[c < 3 ? 0 : k];
  }
  jpeg_compress_struct info{};
  ErrorManager errors;
  install(errors, reinterpret_cast<j_common_ptr>(&info));
  // The output buffer on the heap, for the same reason as the decoder's image.
  struct Buffer {
    unsigned char* data = nullptr;
    unsigned long size = 0;
    ~Buffer() { std::free(data); }
  };
  const auto buffer = std::make_unique<Buffer>();
  if (setjmp(errors.jump)) {
    jpeg_destroy_compress(&info);
    throw CodecError(std::string("JPEG encoder: ") + errors.message);
  }
  jpeg_create_compress(&info);
  jpeg_mem_dest(&info, &buffer->data, &buffer->size);
  info.image_width = JDIMENSION(image.width);
  info.image_height = JDIMENSION(image.height);
  info.input_components = 3;
  info.in_color_space = JCS_RGB;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, quality, TRUE);
  jpeg_start_compress(&info, TRUE);
  while (info.next_scanline < info.image_height) {
    JSAMPROW row = rgb.data() + size_t(info.next_scanline) * size_t(image.width) * 3;
    jpeg_write_scanlines(&info, &row, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  return std::vector<uint8_t>(buffer->data, buffer->data + buffer->size);
}

}  // namespace geolens::codecs
