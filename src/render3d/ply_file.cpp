#include "render3d/ply_file.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/io/file_io.h"
#include "render3d/voxel_types.h"

namespace geolens {

namespace {

constexpr size_t kMaxPlyBytes = size_t(512) << 20;  ///< about twenty million binary triangles

enum class Format { ascii, little_endian, big_endian };

using detail::VoxelType;

struct Property {
  std::string name;
  std::optional<VoxelType> type;        ///< the value's type, or the list's entries' type
  std::optional<VoxelType> count_type;  ///< the list's length type; none for a scalar property
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> properties;
};

std::optional<VoxelType> scalar_named(const std::string& name) {
  if (name == "char" || name == "int8") return VoxelType::int8;
  if (name == "uchar" || name == "uint8") return VoxelType::uint8;
  if (name == "short" || name == "int16") return VoxelType::int16;
  if (name == "ushort" || name == "uint16") return VoxelType::uint16;
  if (name == "int" || name == "int32") return VoxelType::int32;
  if (name == "uint" || name == "uint32") return VoxelType::uint32;
  if (name == "float" || name == "float32") return VoxelType::float32;
  if (name == "double" || name == "float64") return VoxelType::float64;
  return std::nullopt;
}

/// Reads the rows of the body, binary or ASCII, one value at a time.
class BodyReader {
 public:
  BodyReader(const std::string& text, size_t start, Format format, const std::string& path)
      : text_(text), at_(start), format_(format), path_(path) {}

  /// Starts row `row` of `element` (for ASCII: the next line).
  void begin_row(const Element& element, long long row) {
    element_ = &element;
    row_ = row;
    if (format_ != Format::ascii) return;
    while (true) {
      if (at_ >= text_.size()) fail("the file ends");
      const size_t end = std::min(text_.find('\n', at_), text_.size());
      line_.clear();
      line_.str(text_.substr(at_, end - at_));
      at_ = end + 1;
      int c = line_.peek();
      while (c == ' ' || c == '\t' || c == '\r') {
        line_.get();
        c = line_.peek();
      }
      if (c != EOF) break;  // skip blank lines
    }
  }

  double value(VoxelType type) {
    if (format_ == Format::ascii) {
      double v = 0;
      if (!(line_ >> v)) fail("has too few values or one that is not a number");
      return v;
    }
    const size_t n = size_t(detail::voxel_bytes(type));
    if (at_ + n > text_.size()) fail("the file ends");
    const bool swap =
        (format_ == Format::big_endian) == (std::endian::native == std::endian::little);
    const double v = detail::decode_sample(
        reinterpret_cast<const unsigned char*>(text_.data()) + at_, type, swap);
    at_ += n;
    return v;
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InvalidInput("load_ply: '" + path_ + "': " + element_->name + " " + std::to_string(row_) +
                       " of " + std::to_string(element_->count) + ": " + what);
  }

 private:
  const std::string& text_;
  size_t at_;
  Format format_;
  const std::string& path_;
  std::istringstream line_;
  const Element* element_ = nullptr;
  long long row_ = 0;
};

}  // namespace

TriangleMesh load_ply(const std::string& path) {
  const char* f = "load_ply";
  const std::string text = read_file(path, f, "PLY", kMaxPlyBytes);
  const std::string where = "'" + path + "': ";

  // The header: lines up to "end_header".
  std::vector<Element> elements;
  Format format = Format::ascii;
  bool have_format = false;
  size_t at = 0;
  int line_number = 0;
  while (true) {
    require(at < text.size(), f, where + "the header has no end_header line");
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(at, end - at);
    at = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string bad =
        where + "header line " + std::to_string(line_number) + " '" + line.substr(0, 60) + "': ";
    std::istringstream in(line);
    std::string word;
    in >> word;
    if (line_number == 1) {
      require(word == "ply", f, where + "not a PLY file (it does not start with 'ply')");
      continue;
    }
    if (word == "end_header") break;
    if (word.empty() || word == "comment" || word == "obj_info") continue;
    if (word == "format") {
      std::string name, version;
      in >> name >> version;
      if (name == "ascii")
        format = Format::ascii;
      else if (name == "binary_little_endian")
        format = Format::little_endian;
      else if (name == "binary_big_endian")
        format = Format::big_endian;
      else
        require(false, f, bad + "unknown format '" + name + "'");
      require(version == "1.0", f, bad + "unknown version '" + version + "'");
      have_format = true;
    } else if (word == "element") {
      Element element;
      require(bool(in >> element.name >> element.count) && element.count >= 0, f,
              bad + "expected 'element NAME COUNT'");
      elements.push_back(element);
    } else if (word == "property") {
      require(!elements.empty(), f, bad + "a property before any element");
      Property property;
      std::string type;
      in >> type;
      if (type == "list") {
        std::string count_type, entry_type;
        in >> count_type >> entry_type >> property.name;
        property.count_type = scalar_named(count_type);
        property.type = scalar_named(entry_type);
        require(property.count_type && *property.count_type != VoxelType::float32 &&
                    *property.count_type != VoxelType::float64 && property.type,
                f, bad + "unknown list types");
      } else {
        in >> property.name;
        property.type = scalar_named(type);
        require(property.type.has_value(), f, bad + "unknown type '" + type + "'");
      }
      require(!property.name.empty(), f, bad + "the property has no name");
      elements.back().properties.push_back(property);
    } else {
      require(false, f, bad + "unknown keyword '" + word + "'");
    }
  }
  require(have_format, f, where + "the header has no format line");
  // A row takes bytes of the body (binary: a scalar's size, a list's length; ASCII: a character
  // and a separator a value, a line at least), so counts the body cannot hold are refused before
  // any row is read or any array sized by them (a 271-byte file with an element of 10^18 rows
  // and no properties hung; an ASCII one claiming 10^9 vertices ran out of memory).
  const size_t data_bytes = text.size() > at ? text.size() - at : 0;
  for (const Element& e : elements) {
    size_t row_bytes = 0;
    if (format == Format::ascii) {
      row_bytes = std::max<size_t>(1, 2 * e.properties.size());
    } else {
      require(!e.properties.empty() || e.count == 0, f,
              where + "element '" + e.name + "' has " + std::to_string(e.count) +
                  " rows but no properties");
      for (const Property& property : e.properties)
        row_bytes += size_t(detail::voxel_bytes(property.count_type.value_or(*property.type)));
    }
    require(e.count == 0 || size_t(e.count) <= data_bytes / row_bytes, f,
            where + "element '" + e.name + "' claims " + std::to_string(e.count) +
                " rows, more than its " + std::to_string(data_bytes) + " bytes of data hold");
  }

  const Element* vertex = nullptr;
  const Element* face = nullptr;
  for (const Element& e : elements) {
    if (e.name == "vertex") vertex = &e;
    if (e.name == "face") face = &e;
  }
  require(vertex != nullptr, f, where + "no vertex element");
  require(face != nullptr, f, where + "no face element");
  auto find = [](const Element& e, const std::string& name) {
    for (size_t i = 0; i < e.properties.size(); ++i)
      if (e.properties[i].name == name) return int(i);
    return -1;
  };
  const int px = find(*vertex, "x"), py = find(*vertex, "y"), pz = find(*vertex, "z");
  require(px >= 0 && py >= 0 && pz >= 0, f, where + "the vertex element lacks x, y or z");
  for (const int p : {px, py, pz})
    require(!vertex->properties[size_t(p)].count_type, f,
            where + "vertex coordinates must be scalars");
  const int pnx = find(*vertex, "nx"), pny = find(*vertex, "ny"), pnz = find(*vertex, "nz");
  const bool normals = pnx >= 0 && pny >= 0 && pnz >= 0;
  int list = find(*face, "vertex_indices");
  if (list < 0) list = find(*face, "vertex_index");
  require(list >= 0 && face->properties[size_t(list)].count_type.has_value(), f,
          where + "the face element has no vertex_indices list");
  require(vertex->count <= (1LL << 31) - 1 && face->count <= (1LL << 30), f,
          where + "too many vertices or faces");

  TriangleMesh mesh;
  mesh.V.resize(Eigen::Index(vertex->count), 3);
  if (normals) mesh.N.resize(Eigen::Index(vertex->count), 3);
  std::vector<Eigen::Vector3i> triangles;
  BodyReader body(text, at, format, path);
  std::vector<double> values;
  for (const Element& e : elements) {
    for (long long row = 0; row < e.count; ++row) {
      body.begin_row(e, row);
      values.assign(e.properties.size(), 0);
      std::vector<int> corners;
      for (size_t p = 0; p < e.properties.size(); ++p) {
        const Property& property = e.properties[p];
        if (!property.count_type) {
          values[p] = body.value(*property.type);
          continue;
        }
        const double count = body.value(*property.count_type);
        if (count < 0 || count != std::floor(count) || count > 1e6)
          body.fail("a list length of " + std::to_string(count));
        const bool is_corners = &e == face && int(p) == list;
        for (int i = 0; i < int(count); ++i) {
          const double index = body.value(*property.type);
          if (!is_corners) continue;
          if (index != std::floor(index))
            body.fail("names vertex " + number_text(index) + ", not a whole number");
          if (index < 0 || index >= double(vertex->count))
            body.fail("names vertex " + number_text(index) + ", outside [0, " +
                      std::to_string(vertex->count) + ")");
          corners.push_back(int(index));
        }
      }
      if (&e == vertex) {
        mesh.V.row(Eigen::Index(row)) << values[size_t(px)], values[size_t(py)], values[size_t(pz)];
        if (normals)
          mesh.N.row(Eigen::Index(row)) << values[size_t(pnx)], values[size_t(pny)],
              values[size_t(pnz)];
      } else if (&e == face) {
        if (corners.size() < 3)
          body.fail("has " + std::to_string(corners.size()) + " corners, fewer than 3");
        for (size_t i = 1; i + 1 < corners.size(); ++i)
          triangles.emplace_back(corners[0], corners[i], corners[i + 1]);
      }
    }
  }
  mesh.F.resize(Eigen::Index(triangles.size()), 3);
  for (size_t t = 0; t < triangles.size(); ++t) mesh.F.row(Eigen::Index(t)) = triangles[t];
  if (normals)
    for (Eigen::Index v = 0; v < mesh.N.rows(); ++v) {
      const double length = mesh.N.row(v).norm();
      if (length > 0 && std::isfinite(length)) mesh.N.row(v) /= length;
    }
  check_triangle_mesh(mesh, f, path);
  return mesh;
}

}  // namespace geolens
