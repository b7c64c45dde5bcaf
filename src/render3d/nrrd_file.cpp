#include "render3d/nrrd_file.h"

#include <zlib.h>

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

/// A NRRD file, or its detached data, holds at most the samples read and a header.
constexpr size_t kMaxNrrdBytes = kMaxVolumeBytes + (size_t(1) << 20);

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

/// Inflates a gzip (or zlib) stream: exactly `expected` bytes, or fewer if the stream ends.
/// Deflate expands by at most 1032:1 (zlib's FAQ), so no more than that times `size` is
/// allocated whatever a header claims: a gzip bomb's claim costs what its bytes can hold.
std::string inflate_all(const unsigned char* data, size_t size, size_t expected,
                        const std::string& where) {
  constexpr size_t kMaxDeflateRatio = 1032;
  expected = std::min(expected, size * kMaxDeflateRatio + 64);  // a file's size: no overflow
  std::string out(expected, '\0');
  z_stream stream{};
  require(inflateInit2(&stream, 15 + 32) == Z_OK, "load_nrrd", where + "zlib failed to start");
  stream.next_in = const_cast<unsigned char*>(data);
  size_t produced = 0;
  int status = Z_OK;
  size_t remaining_in = size;
  while (produced < expected && status == Z_OK) {
    const unsigned chunk_in = unsigned(std::min<size_t>(remaining_in, 1u << 30));
    const unsigned chunk_out = unsigned(std::min<size_t>(expected - produced, 1u << 30));
    stream.avail_in = chunk_in;
    stream.next_out = reinterpret_cast<unsigned char*>(out.data()) + produced;
    stream.avail_out = chunk_out;
    status = inflate(&stream, Z_NO_FLUSH);
    remaining_in -= chunk_in - stream.avail_in;
    produced += chunk_out - stream.avail_out;
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
            where + "header line " + std::to_string(line_number) + " '" + line.substr(0, 60) +
                "' is not 'field: value'");
    if (colon + 1 < line.size() && line[colon + 1] == '=') continue;  // key:=value
    header.fields[trim(line.substr(0, colon))] = {trim(line.substr(colon + 1)), line_number};
  }
  return header;
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

ScalarVolume load_nrrd(const std::string& path) {
  const char* f = "load_nrrd";
  const std::string where = "'" + path + "': ";
  const std::string text = read_file(path, f, "NRRD", kMaxNrrdBytes);
  Header header = parse_header(text, where);
  auto& fields = header.fields;  // name -> value, line
  auto field = [&](const std::string& name, bool required) {
    require(!required || fields.count(name) > 0, f,
            where + "the header has no '" + name + "' field");
    return header.value(name);
  };
  // Read only: a message built before its field's check (arguments are evaluated first) must
  // not add the field it is about.
  auto bad = [&](const std::string& name, const std::string& what) {
    const auto it = fields.find(name);
    if (it == fields.end()) return where + "the header has no '" + name + "' field";
    return where + "header line " + std::to_string(it->second.second) + " (" + name + ": " +
           it->second.first.substr(0, 60) + "): " + what;
  };

  VoxelType type = VoxelType::uint8;
  require(type_named(field("type", true), type), f, bad("type", "unknown type"));
  require(field("dimension", true) == "3", f, bad("dimension", "only 3D volumes are read"));
  ScalarVolume volume;
  {
    std::istringstream in(field("sizes", true));
    long long sizes[3];
    std::string rest;
    require(bool(in >> sizes[0] >> sizes[1] >> sizes[2]) && !(in >> rest), f,
            bad("sizes", "expected three sizes"));
    for (const long long s : sizes)
      require(s >= 0 && s <= (1 << 16), f, bad("sizes", "a size outside [0, 65536]"));
    volume.nx = int(sizes[0]);
    volume.ny = int(sizes[1]);
    volume.nz = int(sizes[2]);
    require(volume.nx > 0 && volume.ny > 0 && volume.nz > 0, f,
            bad("sizes", "a volume of zero size"));
    require(uint64_t(sizes[0]) * uint64_t(sizes[1]) * uint64_t(sizes[2]) <= kMaxVoxels, f,
            bad("sizes", "more than the " + std::to_string(kMaxVoxels) + " voxels read (2^28)"));
  }
  std::string encoding = field("encoding", true);
  require(encoding == "raw" || encoding == "gzip" || encoding == "gz", f,
          bad("encoding", "only raw and gzip are read"));
  const int bytes = detail::voxel_bytes(type);
  bool swap = false;
  if (bytes > 1) {
    const std::string endian = field("endian", true);
    require(endian == "little" || endian == "big", f, bad("endian", "not little or big"));
    swap = (endian == "big") != (std::endian::native == std::endian::big);
  }
  std::string spacings = field("spacings", false);
  std::string directions = field("space directions", false);
  if (!spacings.empty()) {
    std::istringstream in(spacings);
    for (int k = 0; k < 3; ++k) {
      std::string word;
      require(bool(in >> word), f, bad("spacings", "expected three spacings"));
      const double s = word == "nan" || word == "NaN" ? 1 : std::strtod(word.c_str(), nullptr);
      require(std::isfinite(s) && s > 0, f, bad("spacings", "a spacing that is not positive"));
      volume.spacing[k] = s;
    }
  } else if (!directions.empty()) {
    // "(a,b,c) (d,e,f) (g,h,i)" or "none" for an axis.
    size_t p = 0;
    for (int k = 0; k < 3; ++k) {
      while (p < directions.size() && directions[p] == ' ') ++p;
      if (directions.compare(p, 4, "none") == 0) {
        p += 4;
        continue;
      }
      const size_t close = directions.find(')', p);
      require(p < directions.size() && directions[p] == '(' && close != std::string::npos, f,
              bad("space directions", "expected three (x,y,z) vectors"));
      std::string inner = directions.substr(p + 1, close - p - 1);
      for (char& c : inner)
        if (c == ',') c = ' ';
      std::istringstream in(inner);
      double length2 = 0, c = 0;
      while (in >> c) length2 += c * c;
      const double s = std::sqrt(length2);
      require(std::isfinite(s) && s > 0, f, bad("space directions", "a zero direction"));
      volume.spacing[k] = s;
      p = close + 1;
    }
  }

  // The data: attached after the blank line, or in a detached file.
  const std::string detached_name = header.data_file();
  std::string detached;
  const std::string* data = &text;
  size_t data_start = header.data_start;
  std::string data_where = where;
  if (!detached_name.empty()) {
    const std::string data_path = resolved_data_path(path, detached_name);
    std::error_code error;
    require(std::filesystem::exists(data_path, error), f,
            where + "data file '" + data_path + "' does not exist");
    detached = read_file(data_path, f, "NRRD data", kMaxNrrdBytes);
    data = &detached;
    data_start = 0;
    data_where = where + "data file '" + data_path + "': ";
  } else {
    require(header.attached, f, where + "no data: the header has no blank line and no 'data file'");
  }
  const std::string line_skip = field("line skip", false);
  if (!line_skip.empty()) {
    const std::optional<int> n = read_integer(line_skip);
    require(n && *n >= 0, f, bad("line skip", "not a line count"));
    for (int i = 0; i < *n && data_start < data->size(); ++i) {
      const size_t end = data->find('\n', data_start);
      data_start = end == std::string::npos ? data->size() : end + 1;
    }
  }
  const size_t count = size_t(volume.nx) * size_t(volume.ny) * size_t(volume.nz);
  const size_t expected = count * size_t(bytes);
  require(expected <= kMaxVolumeBytes, f,
          where + "the header claims " + std::to_string(expected) +
              " bytes of samples, more than the " + std::to_string(kMaxVolumeBytes) +
              " read (2^30)");
  const std::string size_text = std::to_string(volume.nx) + " x " + std::to_string(volume.ny) +
                                " x " + std::to_string(volume.nz) + " " +
                                detail::voxel_type_name(type) + " voxels (" +
                                std::to_string(expected) + " bytes)";
  const std::string byte_skip = field("byte skip", false);
  char* skip_end = nullptr;
  const long long skip = byte_skip.empty() ? 0 : std::strtoll(byte_skip.c_str(), &skip_end, 10);
  require(byte_skip.empty() || skip_end == byte_skip.c_str() + byte_skip.size(), f,
          bad("byte skip", "not -1 or a byte count"));
  std::string inflated;
  const unsigned char* samples = nullptr;
  if (encoding == "raw") {
    if (skip == -1) {
      require(data->size() >= expected, f,
              data_where + "the header claims " + size_text + ", the file holds " +
                  std::to_string(data->size()) + " bytes");
      data_start = data->size() - expected;
    } else {
      require(skip >= 0, f, bad("byte skip", "not -1 or a byte count"));
      data_start += size_t(skip);
    }
    const size_t held = data->size() > data_start ? data->size() - data_start : 0;
    require(held >= expected, f,
            data_where + "the header claims " + size_text + ", the data holds " +
                std::to_string(held) + " bytes");
    samples = reinterpret_cast<const unsigned char*>(data->data()) + data_start;
  } else {
    const size_t held = data->size() > data_start ? data->size() - data_start : 0;
    inflated = inflate_all(reinterpret_cast<const unsigned char*>(data->data()) + data_start, held,
                           expected, data_where);
    require(inflated.size() == expected, f,
            data_where + "the header claims " + size_text + ", the gzip data holds " +
                std::to_string(inflated.size()) + " bytes");
    samples = reinterpret_cast<const unsigned char*>(inflated.data());
  }
  volume.values.resize(count);
  detail::decode_voxels(samples, count, type, swap, volume.values.data());
  check_volume(volume, f, path);
  return volume;
}

}  // namespace geolens
