// Fuzzes image decoding: the input is an image file (PNG or JPEG, told apart by content) read by
// load_image, the libspng and libjpeg-turbo codecs behind it. A decoded image of at most 2^16
// pixels is written back as PNG and read again: the pixels must come back unchanged.
// A finding: a crash, a sanitizer report, an exception other than InvalidInput, a hang, an
// allocation past libFuzzer's limit, or a PNG round trip that changes a pixel.
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace geolens;
  const std::string path = fuzz::write_input("input", data, size);
  fuzz::read_or_refuse([&] {
    const Image image = load_image(path);
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
        image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels))
      fuzz::finding("load_image returned an image whose size and pixels disagree");
    if (size_t(image.width) * size_t(image.height) > (size_t(1) << 16)) return;
    const std::string copy = (fuzz::scratch() / "copy.png").string();
    save_image(copy, image);
    const Image back = load_image(copy);
    if (back.width != image.width || back.height != image.height ||
        back.channels != image.channels || back.pixels != image.pixels)
      fuzz::finding("an image written as PNG reads back different");
  });
  return 0;
}
