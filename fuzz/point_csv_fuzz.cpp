// Fuzzes CSV points: the input is a points file ("x,y[,...]" a line, perhaps a header) read by
// parse_point_csv (what `geolens map` reads). A table it reads is written back (point_csv_text)
// and read again: header, points (bit for bit) and the rest of each line must come back, as
// documented.
// A finding: a crash, a sanitizer report, an exception other than InvalidInput from the first
// read, any exception from writing a table read or reading back what was written, a table that
// changes, a hang, an allocation past libFuzzer's limit.
#include <cstring>

#include "fuzz_support.h"
#include "geolens/io/point_csv.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace geolens;
  const std::string text(reinterpret_cast<const char*>(data), size);
  PointTable read;
  try {
    read = parse_point_csv(text, "input");
  } catch (const InvalidInput&) {
    return 0;
  }
  PointTable back;
  try {
    back = parse_point_csv(point_csv_text(read), "written");
  } catch (const std::exception& e) {
    fuzz::finding(std::string("a table read does not write and read back: ") + e.what());
  }
  const bool same_points =
      back.points.rows() == read.points.rows() &&
      std::equal(back.points.data(), back.points.data() + back.points.size(), read.points.data(),
                 [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; });
  if (back.header != read.header || back.rest != read.rest || !same_points)
    fuzz::finding("a table written and read back changed");
  return 0;
}
