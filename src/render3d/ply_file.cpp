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

constexpr const char* kFn = "load_ply";

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
    throw InvalidInput("load_ply: '" + path_ + "': " + quoted_line(element_->name) + " " +
                       std::to_string(row_) + " of " + std::to_string(element_->count) + ": " +
                       what);
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

/// The header's elements, the body's format and where the body starts.
struct Header {
  std::vector<Element> elements;
  Format format = Format::ascii;
  size_t body_start = 0;
};

/// Whether `in` has nothing left but spaces (a header line's words all read).
bool read_whole(std::istringstream& in) {
  std::string rest;
  return !(in >> rest);
}

/// The format of a "format NAME VERSION" line, `in` past its keyword; `bad` starts its messages.
Format read_format(std::istringstream& in, const std::string& bad) {
  std::string name, version;
  in >> name >> version;
  Format format = Format::ascii;
  if (name == "ascii")
    format = Format::ascii;
  else if (name == "binary_little_endian")
    format = Format::little_endian;
  else if (name == "binary_big_endian")
    format = Format::big_endian;
  else
    require(false, kFn, bad + "unknown format '" + quoted_line(name) + "'");
  require(version == "1.0", kFn, bad + "unknown version '" + quoted_line(version) + "'");
  require(read_whole(in), kFn, bad + "expected 'format NAME 1.0'");
  return format;
}

/// The element of an "element NAME COUNT" line, `in` past its keyword.
Element read_element(std::istringstream& in, const std::string& bad) {
  Element element;
  require(bool(in >> element.name >> element.count) && element.count >= 0 && read_whole(in), kFn,
          bad + "expected 'element NAME COUNT'");
  return element;
}

/// The property of a "property TYPE NAME" or "property list COUNT_TYPE ENTRY_TYPE NAME" line,
/// `in` past its keyword.
Property read_property(std::istringstream& in, const std::string& bad) {
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
            kFn, bad + "unknown list types");
  } else {
    in >> property.name;
    property.type = scalar_named(type);
    require(property.type.has_value(), kFn, bad + "unknown type '" + quoted_line(type) + "'");
  }
  require(!property.name.empty(), kFn, bad + "the property has no name");
  require(read_whole(in), kFn, bad + "words after the property's name");
  return property;
}

/// The header of the PLY text `text`: its lines up to "end_header"; `where` names the file.
Header read_header(const std::string& text, const std::string& where) {
  Header header;
  bool have_format = false;
  size_t& at = header.body_start;
  int line_number = 0;
  while (true) {
    require(at < text.size(), kFn, where + "the header has no end_header line");
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(at, end - at);
    at = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string bad =
        where + "header line " + std::to_string(line_number) + " '" + quoted_line(line) + "': ";
    std::istringstream in(line);
    std::string word;
    in >> word;
    if (line_number == 1) {
      require(word == "ply", kFn, where + "not a PLY file (it does not start with 'ply')");
      continue;
    }
    if (word == "end_header") break;
    if (word.empty() || word == "comment" || word == "obj_info") continue;
    if (word == "format") {
      header.format = read_format(in, bad);
      have_format = true;
    } else if (word == "element") {
      header.elements.push_back(read_element(in, bad));
    } else if (word == "property") {
      require(!header.elements.empty(), kFn, bad + "a property before any element");
      header.elements.back().properties.push_back(read_property(in, bad));
    } else {
      require(false, kFn, bad + "unknown keyword '" + quoted_line(word) + "'");
    }
  }
  require(have_format, kFn, where + "the header has no format line");
  return header;
}

/// Refuses an element with more rows than the body of a `text_size`-byte file can hold.
void check_row_counts(const Header& header, size_t text_size, const std::string& where) {
  // A row takes bytes of the body (binary: a scalar's size, a list's length; ASCII: a character
  // and a separator a value, a line at least), so counts the body cannot hold are refused before
  // any row is read or any array sized by them (a 271-byte file with an element of 10^18 rows
  // and no properties hung; an ASCII one claiming 10^9 vertices ran out of memory).
  const size_t at = header.body_start;
  const size_t data_bytes = text_size > at ? text_size - at : 0;
  for (const Element& e : header.elements) {
    size_t row_bytes = 0;
    if (header.format == Format::ascii) {
      row_bytes = std::max<size_t>(1, 2 * e.properties.size());
    } else {
      require(!e.properties.empty() || e.count == 0, kFn,
              where + "element '" + quoted_line(e.name) + "' has " + std::to_string(e.count) +
                  " rows but no properties");
      for (const Property& property : e.properties)
        row_bytes += size_t(detail::voxel_bytes(property.count_type.value_or(*property.type)));
    }
    require(e.count == 0 || size_t(e.count) <= data_bytes / row_bytes, kFn,
            where + "element '" + quoted_line(e.name) + "' claims " + std::to_string(e.count) +
                " rows, more than its " + std::to_string(data_bytes) + " bytes of data hold");
  }
}

/// Where the mesh is among the elements: the vertex and face elements and their properties'
/// indices.
struct Layout {
  const Element* vertex = nullptr;
  const Element* face = nullptr;
  int px = -1, py = -1, pz = -1;     ///< the vertex's x, y and z
  int pnx = -1, pny = -1, pnz = -1;  ///< its nx, ny and nz, -1 where missing
  bool normals = false;              ///< nx, ny and nz all there
  int list = -1;                     ///< the face's corner list
};

/// The index of `e`'s property `name`, -1 if it has none.
int property_index(const Element& e, const std::string& name) {
  for (size_t i = 0; i < e.properties.size(); ++i)
    if (e.properties[i].name == name) return int(i);
  return -1;
}

/// Finds the vertex and face elements and the properties read of them, refusing a header that
/// lacks one or claims more of them than are read.
Layout find_layout(const std::vector<Element>& elements, const std::string& where) {
  Layout layout;
  for (const Element& e : elements) {
    if (e.name == "vertex") layout.vertex = &e;
    if (e.name == "face") layout.face = &e;
  }
  require(layout.vertex != nullptr, kFn, where + "no vertex element");
  require(layout.face != nullptr, kFn, where + "no face element");
  const Element& vertex = *layout.vertex;
  const Element& face = *layout.face;
  layout.px = property_index(vertex, "x");
  layout.py = property_index(vertex, "y");
  layout.pz = property_index(vertex, "z");
  require(layout.px >= 0 && layout.py >= 0 && layout.pz >= 0, kFn,
          where + "the vertex element lacks x, y or z");
  layout.pnx = property_index(vertex, "nx");
  layout.pny = property_index(vertex, "ny");
  layout.pnz = property_index(vertex, "nz");
  for (const int p : {layout.px, layout.py, layout.pz, layout.pnx, layout.pny, layout.pnz}) {
    if (p < 0) continue;  // a missing normal: none are read
    const Property& property = vertex.properties[size_t(p)];
    require(!property.count_type, kFn,
            where + "the vertex property '" + property.name + "' is a list, not a number");
  }
  layout.normals = layout.pnx >= 0 && layout.pny >= 0 && layout.pnz >= 0;
  layout.list = property_index(face, "vertex_indices");
  if (layout.list < 0) layout.list = property_index(face, "vertex_index");
  require(layout.list >= 0 && face.properties[size_t(layout.list)].count_type.has_value(), kFn,
          where + "the face element has no vertex_indices list");
  require(vertex.count <= (1LL << 31) - 1 && face.count <= (1LL << 30), kFn,
          where + "too many vertices or faces");
  return layout;
}

/// Reads a list property's length and entries; appends them to `corners` when they are a face's
/// corners (`is_corners`), each checked to name one of the `vertices` vertices.
void read_list(BodyReader& body, const Property& property, bool is_corners, long long vertices,
               std::vector<int>& corners) {
  const double count = body.value(*property.count_type);
  if (count < 0 || count != std::floor(count) || count > 1e6)
    body.fail("a list length of " + std::to_string(count));
  for (int i = 0; i < int(count); ++i) {
    const double index = body.value(*property.type);
    if (!is_corners) continue;
    if (index != std::floor(index))
      body.fail("names vertex " + number_text(index) + ", not a whole number");
    if (index < 0 || index >= double(vertices))
      body.fail("names vertex " + number_text(index) + ", outside [0, " + std::to_string(vertices) +
                ")");
    corners.push_back(int(index));
  }
}

/// Reads the row `body` is at of element `e`: its scalar properties into `values` (0 for a list),
/// the face's corners into `corners`.
void read_row(BodyReader& body, const Element& e, const Layout& layout, std::vector<double>& values,
              std::vector<int>& corners) {
  values.assign(e.properties.size(), 0);
  for (size_t p = 0; p < e.properties.size(); ++p) {
    const Property& property = e.properties[p];
    if (!property.count_type) {
      values[p] = body.value(*property.type);
      continue;
    }
    const bool is_corners = &e == layout.face && int(p) == layout.list;
    read_list(body, property, is_corners, layout.vertex->count, corners);
  }
}

/// Reads every element's rows in order: the vertices into mesh.V (and mesh.N, sized by the
/// caller), the faces fanned from their first corner into `triangles`.
void read_rows(BodyReader& body, const std::vector<Element>& elements, const Layout& layout,
               TriangleMesh& mesh, std::vector<Eigen::Vector3i>& triangles) {
  std::vector<double> values;
  for (const Element& e : elements) {
    for (long long row = 0; row < e.count; ++row) {
      body.begin_row(e, row);
      std::vector<int> corners;
      read_row(body, e, layout, values, corners);
      if (&e == layout.vertex) {
        mesh.V.row(Eigen::Index(row)) << values[size_t(layout.px)], values[size_t(layout.py)],
            values[size_t(layout.pz)];
        if (layout.normals)
          mesh.N.row(Eigen::Index(row)) << values[size_t(layout.pnx)], values[size_t(layout.pny)],
              values[size_t(layout.pnz)];
      } else if (&e == layout.face) {
        if (corners.size() < 3)
          body.fail("has " + std::to_string(corners.size()) + " corners, fewer than 3");
        for (size_t i = 1; i + 1 < corners.size(); ++i)
          triangles.emplace_back(corners[0], corners[i], corners[i + 1]);
      }
    }
  }
}

/// Sets mesh.F to `triangles` and scales each normal read (if `normals`) to unit length, leaving
/// a zero or non-finite one as it is.
void finish_mesh(const std::vector<Eigen::Vector3i>& triangles, bool normals, TriangleMesh& mesh) {
  mesh.F.resize(Eigen::Index(triangles.size()), 3);
  for (size_t t = 0; t < triangles.size(); ++t) mesh.F.row(Eigen::Index(t)) = triangles[t];
  if (normals)
    for (Eigen::Index v = 0; v < mesh.N.rows(); ++v) {
      const double length = mesh.N.row(v).norm();
      if (length > 0 && std::isfinite(length)) mesh.N.row(v) /= length;
    }
}

}  // namespace

TriangleMesh load_ply(const std::string& path, size_t max_vertices) {
  require(max_vertices >= 1, kFn, "max_vertices must be >= 1, got 0");
  const std::string text = read_file(path, kFn, "PLY", mesh_bytes_limit(max_vertices));
  const std::string where = "'" + path + "': ";
  const Header header = read_header(text, where);
  check_row_counts(header, text.size(), where);
  const Layout layout = find_layout(header.elements, where);
  require(uint64_t(layout.vertex->count) <= max_vertices, kFn,
          where + vertex_limit_message(uint64_t(layout.vertex->count), max_vertices));

  TriangleMesh mesh;
  mesh.V.resize(Eigen::Index(layout.vertex->count), 3);
  if (layout.normals) mesh.N.resize(Eigen::Index(layout.vertex->count), 3);
  std::vector<Eigen::Vector3i> triangles;
  BodyReader body(text, header.body_start, header.format, path);
  read_rows(body, header.elements, layout, mesh, triangles);
  finish_mesh(triangles, layout.normals, mesh);
  check_triangle_mesh(mesh, kFn, path);
  return mesh;
}

}  // namespace geolens
