// Fuzzes mask reading: the input is a mask image (PNG or JPEG) read by load_mask; one of at most
// 2^16 pixels is then read as a lens spec `mask:FILE` of its size (parse_lens_spec: each blob a
// region, outlined by mask_contours, checked by validate_lens), as the CLI's --lens reads it.
// Larger masks are only decoded: their blob analysis is legitimately slow, not a finding.
// A finding: a crash, a sanitizer report, an exception other than InvalidInput, a hang, an
// allocation past libFuzzer's limit.
#include "fuzz_support.h"
#include "geolens/lens/lens_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace geolens;
  const std::string path = fuzz::write_input("mask", data, size);
  fuzz::read_or_refuse([&] {
    const Image mask = load_mask(path);
    if (size_t(mask.width) * size_t(mask.height) > (size_t(1) << 16)) return;
    std::vector<std::string> warnings;
    parse_lens_spec("mask:" + path, 2, Profile::kGaussian, 0, mask.width, mask.height, &warnings);
  });
  return 0;
}
