// Fuzzes polygon files: the input is a polygon file ('x y' a line) read as the lens spec
// `polygon:FILE` for a 256 x 256 image (parse_lens_spec: read_polygon_file, simplify_loop,
// validate_polygon, Region::polygon, validate_lens), as the CLI's --lens reads it.
// A finding: a crash, a sanitizer report, an exception other than InvalidInput, a hang, an
// allocation past libFuzzer's limit.
#include "fuzz_support.h"
#include "geolens/lens/lens_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace geolens;
  const std::string path = fuzz::write_input("polygon.txt", data, size);
  fuzz::read_or_refuse(
      [&] { parse_lens_spec("polygon:" + path, 2, Profile::kGaussian, 0, 256, 256); });
  return 0;
}
