#include "render3d/obj_file.h"

#include <tiny_obj_loader.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/io/file_io.h"

namespace geolens {

namespace {

/// The first line of tinyobjloader's message, without its trailing newline.
std::string first_line(const std::string& text) {
  const size_t end = text.find('\n');
  return end == std::string::npos ? text : text.substr(0, end);
}

// Refuses what tinyobjloader reads without a word: a vertex coordinate that is not a finite
// number ("v nan 0 0" was accepted) and a face index beyond int's range (one of 20 digits was
// read as some other vertex), and more than `max_vertices` vertices, before tinyobjloader
// holds them.
void check_numbers(const std::string& text, const std::string& path, size_t max_vertices) {
  std::istringstream lines(text);
  std::string line;
  size_t vertices = 0;
  for (int number = 1; std::getline(lines, line); ++number) {
    std::istringstream words(line);
    std::string kind, word;
    words >> kind;
    if (kind != "v" && kind != "f") continue;
    const std::string at = "'" + path + "': line " + std::to_string(number) + ": ";
    int k = 0;
    for (; words >> word; ++k) {
      if (kind == "v") {
        double value = 0;
        const auto [end, status] = std::from_chars(word.data(), word.data() + word.size(), value);
        require(k >= 3 || (status == std::errc() && std::isfinite(value)), "load_obj",
                at + "vertex coordinate '" + quoted_line(word) + "' is not a finite number");
      } else {
        const std::string index = word.substr(0, word.find('/'));
        long long value = 0;
        const auto [end, status] =
            std::from_chars(index.data(), index.data() + index.size(), value);
        require(status == std::errc() && std::llabs(value) <= std::numeric_limits<int>::max(),
                "load_obj", at + "face index '" + quoted_line(index) + "' is out of range");
      }
    }
    require(kind != "v" || k >= 3, "load_obj",
            at + "a vertex has " + std::to_string(k) + " coordinates, 3 needed");
    vertices += kind == "v";
    require(vertices <= max_vertices, "load_obj",
            at + vertex_limit_message(vertices, max_vertices));
  }
}

}  // namespace

TriangleMesh load_obj(const std::string& path, size_t max_vertices) {
  const char* f = "load_obj";
  require(max_vertices >= 1, f, "max_vertices must be >= 1, got 0");
  const std::string text = read_file(path, f, "OBJ", mesh_bytes_limit(max_vertices));
  check_numbers(text, path, max_vertices);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // No material text: materials are not used, and a missing .mtl must not matter.
  const bool parsed = reader.ParseFromString(text, "", config);
  require(
      parsed && reader.Error().empty(), f,
      "'" + path + "': " +
          (reader.Error().empty() ? std::string("not an OBJ file") : first_line(reader.Error())));
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  TriangleMesh mesh;
  const Eigen::Index vertices = Eigen::Index(attrib.vertices.size() / 3);
  mesh.V.resize(vertices, 3);
  for (Eigen::Index v = 0; v < vertices; ++v)
    for (int k = 0; k < 3; ++k) mesh.V(v, k) = attrib.vertices[size_t(3 * v + k)];

  size_t triangles = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes())
    triangles += shape.mesh.num_face_vertices.size();
  mesh.F.resize(Eigen::Index(triangles), 3);
  std::vector<int> normal_of(size_t(vertices), -1);  // -1: none yet, -2: inconsistent
  bool normals = !attrib.normals.empty();
  Eigen::Index row = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    size_t corner = 0;
    for (const unsigned char count : shape.mesh.num_face_vertices) {
      require(count == 3, f,
              "'" + path + "': face " + std::to_string(row) + " has " + std::to_string(count) +
                  " corners after triangulation");
      for (int k = 0; k < 3; ++k, ++corner) {
        const tinyobj::index_t index = shape.mesh.indices[corner];
        require(index.vertex_index >= 0 && index.vertex_index < vertices, f,
                "'" + path + "': face " + std::to_string(row) + " names vertex " +
                    std::to_string(index.vertex_index + 1) + " of " + std::to_string(vertices));
        mesh.F(row, k) = index.vertex_index;
        int& n = normal_of[size_t(index.vertex_index)];
        if (index.normal_index < 0 || size_t(index.normal_index) * 3 >= attrib.normals.size())
          normals = false;
        else if (n == -1)
          n = index.normal_index;
        else if (n != index.normal_index)
          normals = false;
      }
      ++row;
    }
  }
  if (normals) {
    mesh.N = Eigen::MatrixXd::Zero(vertices, 3);
    for (Eigen::Index v = 0; v < vertices; ++v) {
      const int n = normal_of[size_t(v)];
      if (n < 0) continue;
      const Eigen::RowVector3d normal(attrib.normals[size_t(3 * n)],
                                      attrib.normals[size_t(3 * n + 1)],
                                      attrib.normals[size_t(3 * n + 2)]);
      if (normal.norm() > 0) mesh.N.row(v) = normal.normalized();
    }
  }
  check_triangle_mesh(mesh, f, path);
  return mesh;
}

}  // namespace geolens
