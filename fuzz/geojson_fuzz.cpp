// Fuzzes GeoJSON: the input is a GeoJSON document read by parse_geojson (what read_geojson and
// `geolens map` read). A document it reads is written back (geojson_text), read again and written
// again: the two texts must be equal, since a write / read round trip is documented to be exact.
// A finding: a crash, a sanitizer report, an exception other than InvalidInput from the first
// read, any exception from writing a document read or reading back what was written, texts that
// differ, a hang, an allocation past libFuzzer's limit.
#include "fuzz_support.h"
#include "geolens/io/geojson.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace geolens;
  const std::string text(reinterpret_cast<const char*>(data), size);
  VectorData read;
  try {
    read = parse_geojson(text, "input");
  } catch (const InvalidInput&) {
    return 0;
  }
  std::string written, again;
  try {
    written = geojson_text(read);
    again = geojson_text(parse_geojson(written, "written"));
  } catch (const std::exception& e) {
    fuzz::finding(std::string("a document read does not write and read back: ") + e.what());
  }
  if (again != written)
    fuzz::finding("a document written, read and written again changed:\n" + written + "\n" + again);
  return 0;
}
