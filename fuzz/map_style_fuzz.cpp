// Fuzzes map styles: the input is a style JSON document (--style of a vector map) read by
// parse_map_style.
// A finding: a crash, a sanitizer report, an exception other than InvalidInput, a hang, an
// allocation past libFuzzer's limit.
#include "fuzz_support.h"
#include "geolens/source/map_style.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace geolens;
  const std::string text(reinterpret_cast<const char*>(data), size);
  fuzz::read_or_refuse([&] { parse_map_style(text, "input"); });
  return 0;
}
