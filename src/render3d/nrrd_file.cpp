#include "render3d/nrrd_file.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/core/parse.h"
#include "geolens/io/file_io.h"
#include "render3d/voxel_types.h"

namespace geolens {

namespace {

constexpr const char* kFn = "load_nrrd";

/// A NRRD file, or its detached data, holds at most the samples read and a header.
// The most bytes of a NRRD file (or its detached data) read with a limit of `max_voxels`: its
// samples' limit and a MiB of header.
size_t nrrd_bytes_limit(size_t max_voxels) {
  return volume_bytes_limit(max_voxels) + (size_t(1) << 20);
}

using detail::VoxelType;

bool type_named(const std::string& name, VoxelType& type) {
  static const std::pair<const char*, VoxelType> names[] = {
      {"signed char", VoxelType::int8},
      {"int8", VoxelType::int8},
      {"int8_t", VoxelType::int8},
      {"uchar", VoxelType::uint8},
      {"unsigned char", VoxelType::uint8},
      {"uint8", VoxelType::uint8},
      {"uint8_t", VoxelType::uint8},
      {"short", VoxelType::int16},
      {"short int", VoxelType::int16},
      {"signed short", VoxelType::int16},
      {"signed short int", VoxelType::int16},
      {"int16", VoxelType::int16},
      {"int16_t", VoxelType::int16},
      {"ushort", VoxelType::uint16},
      {"unsigned short", VoxelType::uint16},
      {"unsigned short int", VoxelType::uint16},
      {"uint16", VoxelType::uint16},
      {"uint16_t", VoxelType::uint16},
      {"int", VoxelType::int32},
      {"signed int", VoxelType::int32},
      {"int32", VoxelType::int32},
      {"int32_t", VoxelType::int32},
      {"uint", VoxelType::uint32},
      {"unsigned int", VoxelType::uint32},
      {"uint32", VoxelType::uint32},
      {"uint32_t", VoxelType::uint32},
      {"float", VoxelType::float32},
      {"double", VoxelType::float64},
  };
  for (const auto& [text, value] : names)
    if (name == text) {
      type = value;
      return true;
    }
  return false;
}

std::string trim(const std::string& s) {
  const size_t first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

/// Inflates a gzip (or zlib) stream: drops its first `skip` bytes (`skipped` is set to the bytes
/// dropped) and returns the `expected` bytes after them, or fewer if the stream ends.
/// Deflate expands by at most 1032:1 (zlib's FAQ), so no more than that times `size` is
/// allocated whatever a header claims: a gzip bomb's claim costs what its bytes can hold.
std::string inflate_all(const unsigned char* data, size_t size, size_t skip, size_t expected,
                        const std::string& where, size_t& skipped) {
  constexpr size_t kMaxDeflateRatio = 1032;
  expected = std::min(expected, size * kMaxDeflateRatio + 64);  // a file's size: no overflow
  std::string out(expected, '\0');
  std::vector<unsigned char> dropped(std::min<size_t>(skip, 1u << 16));  // the skipped bytes
  z_stream stream{};
  require(inflateInit2(&stream, 15 + 32) == Z_OK, "load_nrrd", where + "zlib failed to start");
  stream.next_in = const_cast<unsigned char*>(data);
  skipped = 0;
  size_t produced = 0;
  int status = Z_OK;
  size_t remaining_in = size;
  while (produced < expected && status == Z_OK) {
    const bool skipping = skipped < skip;
    const unsigned chunk_in = unsigned(std::min<size_t>(remaining_in, 1u << 30));
    const unsigned chunk_out = unsigned(skipping ? std::min(skip - skipped, dropped.size())
                                                 : std::min<size_t>(expected - produced, 1u << 30));
    stream.avail_in = chunk_in;
    stream.next_out =
        skipping ? dropped.data() : reinterpret_cast<unsigned char*>(out.data()) + produced;
    stream.avail_out = chunk_out;
    status = inflate(&stream, Z_NO_FLUSH);
    remaining_in -= chunk_in - stream.avail_in;
    (skipping ? skipped : produced) += chunk_out - stream.avail_out;
    if (status == Z_BUF_ERROR && remaining_in == 0) break;  // input ended early
    if (status == Z_BUF_ERROR) status = Z_OK;
  }
  const std::string message = stream.msg != nullptr ? stream.msg : "";
  inflateEnd(&stream);
  require(status == Z_OK || status == Z_STREAM_END || status == Z_BUF_ERROR, "load_nrrd",
          where + "corrupt gzip data (" + (message.empty() ? "zlib error" : message) + ")");
  out.resize(produced);
  return out;
}

// A detached data file's name (as the header gives it) resolved against the header's folder.
std::string resolved_data_path(const std::string& header, const std::string& name) {
  const std::filesystem::path named(name);
  return named.is_absolute() ? named.string()
                             : (std::filesystem::path(header).parent_path() / named).string();
}

// The header of the NRRD text `text`, `where` naming its file for messages: every "field: value"
// line by name (its value and line number; key:=value pairs left out), where the data would start
// and whether a blank line ends the header (the data attached after it). Throws InvalidInput
// naming "load_nrrd" for a text without the magic or with a line that is not "field: value".
struct Header {
  std::map<std::string, std::pair<std::string, int>> fields;
  size_t data_start = 0;
  bool attached = false;

  // The value of field `name`, empty if there is none.
  std::string value(const std::string& name) const {
    const auto it = fields.find(name);
    return it == fields.end() ? std::string() : it->second.first;
  }
  // The detached data file as the header names it ("data file" or "datafile"), empty if none.
  std::string data_file() const {
    const std::string name = value("data file");
    return name.empty() ? value("datafile") : name;
  }
};

Header parse_header(const std::string& text, const std::string& where) {
  const char* f = "load_nrrd";
  require(text.compare(0, 7, "NRRD000") == 0 && text.size() > 8 && text[7] >= '1' && text[7] <= '5',
          f, where + "not a NRRD file (it does not start with NRRD0001 - NRRD0005)");
  Header header;
  size_t& at = header.data_start;
  int line_number = 0;
  while (at < text.size()) {
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(at, end - at);
    at = end + 1;
    ++line_number;
    if (line_number == 1 || (!line.empty() && line[0] == '#')) continue;
    if (trim(line).empty()) {
      header.attached = true;
      break;
    }
    const size_t colon = line.find(':');
    require(colon != std::string::npos, f,
            where + "header line " + std::to_string(line_number) + " '" + quoted_line(line) +
                "' is not 'field: value'");
    if (colon + 1 < line.size() && line[colon + 1] == '=') continue;  // key:=value
    header.fields[trim(line.substr(0, colon))] = {trim(line.substr(colon + 1)), line_number};
  }
  return header;
}

/// The header's fields as load_nrrd reads them, `where` naming the file in messages.
struct HeaderFields {
  const Header& header;
  const std::string& where;

  // The value of field `name` (empty if there is none); refused if `required` and missing.
  std::string field(const std::string& name, bool required) const {
    require(!required || header.fields.count(name) > 0, kFn,
            where + "the header has no '" + name + "' field");
    return header.value(name);
  }
  // The message that field `name` has `what` wrong with it, naming its line. Read only: a
  // message built before its field's check (arguments are evaluated first) must not add the
  // field it is about.
  std::string bad(const std::string& name, const std::string& what) const {
    const auto it = header.fields.find(name);
    if (it == header.fields.end()) return where + "the header has no '" + name + "' field";
    return where + "header line " + std::to_string(it->second.second) + " (" + name + ": " +
           quoted_line(it->second.first) + "): " + what;
  }
};

/// The voxel type the "type" field names.
VoxelType voxel_type(const HeaderFields& h) {
  VoxelType type = VoxelType::uint8;
  require(type_named(h.field("type", true), type), kFn, h.bad("type", "unknown type"));
  return type;
}

/// Sets the volume's nx, ny and nz from the "sizes" field, refusing a size out of range or a
/// volume of no or too many voxels.
void read_sizes(const HeaderFields& h, ScalarVolume& volume, size_t max_voxels) {
  std::istringstream in(h.field("sizes", true));
  long long sizes[3];
  std::string rest;
  require(bool(in >> sizes[0] >> sizes[1] >> sizes[2]) && !(in >> rest), kFn,
          h.bad("sizes", "expected three sizes"));
  for (const long long s : sizes)
    require(s >= 0 && s <= (1 << 16), kFn, h.bad("sizes", "a size outside [0, 65536]"));
  volume.nx = int(sizes[0]);
  volume.ny = int(sizes[1]);
  volume.nz = int(sizes[2]);
  require(volume.nx > 0 && volume.ny > 0 && volume.nz > 0, kFn,
          h.bad("sizes", "a volume of zero size"));
  const uint64_t voxels = uint64_t(sizes[0]) * uint64_t(sizes[1]) * uint64_t(sizes[2]);
  require(voxels <= max_voxels, kFn, h.bad("sizes", voxel_limit_message(voxels, max_voxels)));
}

/// Whether samples of several bytes are swapped to the machine's order (the "endian" field).
bool byte_swap(const HeaderFields& h) {
  const std::string endian = h.field("endian", true);
  require(endian == "little" || endian == "big", kFn, h.bad("endian", "not little or big"));
  return (endian == "big") != (std::endian::native == std::endian::big);
}

/// Sets the volume's spacing from the "spacings" field: three numbers, "nan" for 1.
void read_spacings(const HeaderFields& h, const std::string& spacings, ScalarVolume& volume) {
  std::istringstream in(spacings);
  std::string word;
  for (int k = 0; k < 3; ++k) {
    require(bool(in >> word), kFn, h.bad("spacings", "expected three spacings"));
    const std::optional<double> s = word == "nan" || word == "NaN" ? 1.0 : read_number(word);
    require(s.has_value(), kFn, h.bad("spacings", "a spacing that is not a number"));
    require(*s > 0, kFn, h.bad("spacings", "a spacing that is not positive"));
    volume.spacing[k] = *s;
  }
  require(!(in >> word), kFn, h.bad("spacings", "expected three spacings"));
}

/// Sets the volume's spacing from the lengths of the "space directions" field's vectors, an
/// axis "none" keeping its spacing.
void read_directions(const HeaderFields& h, const std::string& directions, ScalarVolume& volume) {
  // "(a,b,c) (d,e,f) (g,h,i)" or "none" for an axis.
  size_t p = 0;
  for (int k = 0; k < 3; ++k) {
    while (p < directions.size() && directions[p] == ' ') ++p;
    if (directions.compare(p, 4, "none") == 0) {
      p += 4;
      continue;
    }
    const size_t close = directions.find(')', p);
    require(p < directions.size() && directions[p] == '(' && close != std::string::npos, kFn,
            h.bad("space directions", "expected three (x,y,z) vectors"));
    // Its components, comma-separated numbers (spaces around them allowed).
    std::istringstream in(directions.substr(p + 1, close - p - 1));
    double length2 = 0;
    for (std::string c; std::getline(in, c, ',');) {
      const size_t first = c.find_first_not_of(' '), last = c.find_last_not_of(' ');
      const std::optional<double> x = first == std::string::npos
                                          ? std::nullopt
                                          : read_number(c.substr(first, last - first + 1));
      require(x.has_value(), kFn,
              h.bad("space directions", "a vector component that is not a number"));
      length2 += *x * *x;
    }
    const double s = std::sqrt(length2);
    require(std::isfinite(s) && s > 0, kFn, h.bad("space directions", "a zero direction"));
    volume.spacing[k] = s;
    p = close + 1;
  }
  require(directions.find_first_not_of(' ', p) == std::string::npos, kFn,
          h.bad("space directions", "expected three (x,y,z) vectors"));
}

/// The bytes the samples are read from: the header's text (attached data) or a detached file's.
struct Data {
  bool is_detached = false;
  std::string detached;  ///< the detached file's bytes
  size_t start = 0;      ///< where the data starts in them
  std::string where;     ///< names the file holding the data, for messages

  const std::string& bytes(const std::string& text) const { return is_detached ? detached : text; }
};

/// The data: attached after the header's blank line, or in the detached file it names (read).
Data find_data(const Header& header, const std::string& path, const std::string& where,
               size_t max_bytes) {
  const std::string detached_name = header.data_file();
  Data data;
  data.start = header.data_start;
  data.where = where;
  if (!detached_name.empty()) {
    // The name comes from the file: none of its characters may reach the terminal as a control.
    require(std::none_of(detached_name.begin(), detached_name.end(),
                         [](unsigned char c) { return c < 0x20 || c == 0x7f; }),
            kFn,
            where + "data file '" + quoted_line(detached_name) +
                "': a file name with control characters");
    const std::string data_path = resolved_data_path(path, detached_name);
    std::error_code error;
    require(std::filesystem::exists(data_path, error), kFn,
            where + "data file '" + data_path + "' does not exist");
    data.detached = read_file(data_path, kFn, "NRRD data", max_bytes);
    data.is_detached = true;
    data.start = 0;
    data.where = where + "data file '" + data_path + "': ";
  } else {
    require(header.attached, kFn,
            where + "no data: the header has no blank line and no 'data file'");
  }
  return data;
}

/// Moves `start` past the lines of `bytes` the "line skip" field skips.
void skip_lines(const HeaderFields& h, const std::string& bytes, size_t& start) {
  const std::string line_skip = h.field("line skip", false);
  if (line_skip.empty()) return;
  const std::optional<int> n = read_integer(line_skip);
  require(n && *n >= 0, kFn, h.bad("line skip", "not a line count"));
  for (int i = 0; i < *n && start < bytes.size(); ++i) {
    const size_t end = bytes.find('\n', start);
    start = end == std::string::npos ? bytes.size() : end + 1;
  }
}

/// The "byte skip" field's value: 0 if there is none, else a whole number (-1: the samples end
/// the file), not checked further.
long long byte_skip(const HeaderFields& h) {
  const std::string byte_skip = h.field("byte skip", false);
  char* skip_end = nullptr;
  const long long skip = byte_skip.empty() ? 0 : std::strtoll(byte_skip.c_str(), &skip_end, 10);
  require(byte_skip.empty() || skip_end == byte_skip.c_str() + byte_skip.size(), kFn,
          h.bad("byte skip", "not -1 or a byte count"));
  return skip;
}

/// The raw samples, `expected` bytes after the byte skip `skip`, checked to be there; `size_text`
/// says what the header claims.
const unsigned char* raw_samples(const HeaderFields& h, const std::string& bytes, const Data& data,
                                 long long skip, size_t expected, const std::string& size_text) {
  size_t start = data.start;
  if (skip == -1) {
    require(bytes.size() >= expected, kFn,
            data.where + "the header claims " + size_text + ", the file holds " +
                std::to_string(bytes.size()) + " bytes");
    start = bytes.size() - expected;
  } else {
    require(skip >= 0, kFn, h.bad("byte skip", "not -1 or a byte count"));
    start += size_t(skip);
  }
  const size_t held = bytes.size() > start ? bytes.size() - start : 0;
  require(held >= expected, kFn,
          data.where + "the header claims " + size_text + ", the data holds " +
              std::to_string(held) + " bytes");
  return reinterpret_cast<const unsigned char*>(bytes.data()) + start;
}

/// The gzip data inflated, its first `skip` bytes skipped (the byte skip applies to the inflated
/// data; -1 is read only with raw encoding), checked to be the `expected` bytes `size_text` claims.
std::string gzip_samples(const HeaderFields& h, const std::string& bytes, const Data& data,
                         long long skip, size_t expected, const std::string& size_text,
                         size_t max_bytes) {
  require(skip != -1, kFn, h.bad("byte skip", "-1 is read only with raw encoding"));
  require(skip >= 0, kFn, h.bad("byte skip", "not a byte count"));
  // What is inflated is held to a raw file's limit: a skip costs no more than its bytes would.
  require(size_t(skip) <= max_bytes - expected, kFn,
          h.bad("byte skip", "with the samples, more than the " + std::to_string(max_bytes) +
                                 " bytes of data read"));
  const size_t held = bytes.size() > data.start ? bytes.size() - data.start : 0;
  size_t skipped = 0;
  std::string inflated =
      inflate_all(reinterpret_cast<const unsigned char*>(bytes.data()) + data.start, held,
                  size_t(skip), expected, data.where, skipped);
  require(skipped == size_t(skip), kFn,
          data.where + "the byte skip (" + std::to_string(skip) +
              ") is beyond the end of the gzip data (" + std::to_string(skipped) + " bytes)");
  require(inflated.size() == expected, kFn,
          data.where + "the header claims " + size_text + ", the gzip data holds " +
              std::to_string(inflated.size()) + " bytes" +
              (skip > 0 ? " after the byte skip" : ""));
  return inflated;
}

}  // namespace

std::string nrrd_data_path(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return "";
  // A header is text lines before the data: its first MiB holds it.
  std::string text(size_t(1) << 20, '\0');
  std::ifstream in(path, std::ios::binary);
  in.read(text.data(), std::streamsize(text.size()));
  text.resize(size_t(in.gcount()));
  try {
    const std::string name = parse_header(text, "'" + path + "': ").data_file();
    return name.empty() ? name : resolved_data_path(path, name);
  } catch (const InvalidInput&) {
    return "";  // load_nrrd names what is wrong
  }
}

ScalarVolume load_nrrd(const std::string& path, size_t max_voxels) {
  require(max_voxels >= 1, kFn, "max_voxels must be >= 1, got 0");
  const size_t max_bytes = nrrd_bytes_limit(max_voxels);
  const std::string where = "'" + path + "': ";
  const std::string text = read_file(path, kFn, "NRRD", max_bytes);
  const Header header = parse_header(text, where);
  const HeaderFields h{header, where};
  const VoxelType type = voxel_type(h);
  require(h.field("dimension", true) == "3", kFn, h.bad("dimension", "only 3D volumes are read"));
  ScalarVolume volume;
  read_sizes(h, volume, max_voxels);
  const std::string encoding = h.field("encoding", true);
  require(encoding == "raw" || encoding == "gzip" || encoding == "gz", kFn,
          h.bad("encoding", "only raw and gzip are read"));
  const int bytes = detail::voxel_bytes(type);
  const bool swap = bytes > 1 && byte_swap(h);
  const std::string spacings = h.field("spacings", false);
  const std::string directions = h.field("space directions", false);
  if (!spacings.empty())
    read_spacings(h, spacings, volume);
  else if (!directions.empty())
    read_directions(h, directions, volume);

  Data data = find_data(header, path, where, max_bytes);
  const std::string& data_bytes = data.bytes(text);
  skip_lines(h, data_bytes, data.start);
  const size_t count = size_t(volume.nx) * size_t(volume.ny) * size_t(volume.nz);
  const size_t expected = count * size_t(bytes);
  const size_t max_samples = volume_bytes_limit(max_voxels);
  require(expected <= max_samples, kFn,
          where + "the header claims " + std::to_string(expected) +
              " bytes of samples, more than the " + std::to_string(max_samples) +
              " read (4 a voxel of max_voxels, at least 2^30)");
  const std::string size_text = std::to_string(volume.nx) + " x " + std::to_string(volume.ny) +
                                " x " + std::to_string(volume.nz) + " " +
                                detail::voxel_type_name(type) + " voxels (" +
                                std::to_string(expected) + " bytes)";
  const long long skip = byte_skip(h);
  std::string inflated;
  const unsigned char* samples = nullptr;
  if (encoding == "raw") {
    samples = raw_samples(h, data_bytes, data, skip, expected, size_text);
  } else {
    inflated = gzip_samples(h, data_bytes, data, skip, expected, size_text, max_bytes);
    samples = reinterpret_cast<const unsigned char*>(inflated.data());
  }
  volume.values.resize(count);
  detail::decode_voxels(samples, count, type, swap, volume.values.data());
  check_volume(volume, kFn, path);
  return volume;
}

}  // namespace geolens
