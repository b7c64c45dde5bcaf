// The PLY reader on small files written by the test: ASCII, binary little- and big-endian files
// of the same mesh read alike (other elements and properties, lists among them, skipped), faces
// fanned from their first corner, normals read when nx, ny and nz are all there, and bad headers
// and rows refused with InvalidInput naming load_ply, the file and the line or row at fault.

#include "render3d/ply_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "support/refusal.h"
#include "support/scratch_folder.h"

namespace geolens {
namespace {

class PlyFile : public testing::ScratchFolderTest {
 protected:
  /// The message of the InvalidInput load_ply throws for `bytes` written as `name`, checked to
  /// start with the reader's name and to name the file.
  std::string refusal(const std::string& name, const std::string& bytes) {
    const std::string file = write(name, bytes);
    const std::string message = test::refusal([&] { load_ply(file); });
    EXPECT_EQ(message.rfind("load_ply: '" + file + "'", 0), 0u) << message;
    return message;
  }
};

/// `value`'s bytes appended to `s`, most significant first when `big`.
template <typename T>
void append(std::string& s, T value, bool big) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big) std::reverse(bytes, bytes + sizeof(T));
  s.append(bytes, sizeof(T));
}

// A square pyramid: four base corners, an apex; the base as one quad, four triangle sides.
const double kPyramid[5][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0.25, -0.5, 3}};
const std::vector<std::vector<int>> kPyramidFaces = {
    {0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};

/// The pyramid in `format` ("ascii", "binary_little_endian", "binary_big_endian"), its vertices
/// with x double, y float, z int16 and two properties to skip (a colour and a list), an element
/// between vertices and faces to skip, and a flag after each face's list.
std::string pyramid(const std::string& format) {
  std::string s = "ply\nformat " + format +
                  " 1.0\ncomment made by the test\nobj_info nothing\n"
                  "element vertex 5\nproperty double x\nproperty uchar red\nproperty float y\n"
                  "property list uchar int16 tags\nproperty short z\n"
                  "element material 2\nproperty list uint8 float weights\nproperty int id\n"
                  "element face 5\nproperty list uchar int vertex_indices\nproperty uchar flag\n"
                  "end_header\n";
  const bool ascii = format == "ascii", big = format == "binary_big_endian";
  for (int v = 0; v < 5; ++v) {
    const int tags = v % 3;  // lists of 0, 1 or 2 entries
    if (ascii) {
      std::ostringstream row;
      row << kPyramid[v][0] << " 200 " << kPyramid[v][1] << " " << tags;
      for (int t = 0; t < tags; ++t) row << " " << -7 * t;
      row << " " << int(kPyramid[v][2]) << "\n";
      s += row.str();
    } else {
      append(s, double(kPyramid[v][0]), big);
      append(s, uint8_t(200), big);
      append(s, float(kPyramid[v][1]), big);
      append(s, uint8_t(tags), big);
      for (int t = 0; t < tags; ++t) append(s, int16_t(-7 * t), big);
      append(s, int16_t(kPyramid[v][2]), big);
    }
  }
  for (int m = 0; m < 2; ++m) {
    if (ascii) {
      s += m == 0 ? "3 0.5 0.25 0.125 17\n" : "0 18\n";
    } else {
      append(s, uint8_t(m == 0 ? 3 : 0), big);
      if (m == 0)
        for (const float w : {0.5f, 0.25f, 0.125f}) append(s, w, big);
      append(s, int32_t(17 + m), big);
    }
  }
  for (const std::vector<int>& face : kPyramidFaces) {
    if (ascii) {
      std::ostringstream row;
      row << face.size();
      for (const int i : face) row << " " << i;
      row << " 1\n";
      s += row.str();
    } else {
      append(s, uint8_t(face.size()), big);
      for (const int i : face) append(s, int32_t(i), big);
      append(s, uint8_t(1), big);
    }
  }
  return s;
}

TEST_F(PlyFile, AnAsciiFileReadsItsPositionsAndFacesExactlyWhateverItsLineEnds) {
  const TriangleMesh mesh = load_ply(write("pyramid.ply", pyramid("ascii")));
  ASSERT_EQ(mesh.V.rows(), 5);
  for (int v = 0; v < 5; ++v)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(mesh.V(v, k), kPyramid[v][k]) << v << ", " << k;
  Eigen::MatrixXi F(6, 3);
  F << 0, 3, 2, 0, 2, 1, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4;
  EXPECT_EQ(mesh.F, F);
  EXPECT_EQ(mesh.N.rows(), 0);
  // Windows line ends, blank lines between rows, and "vertex_index" for the list's name.
  const TriangleMesh crlf = load_ply(
      write("crlf.ply",
            "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float x\r\nproperty float "
            "y\r\nproperty float z\r\nelement face 1\r\nproperty list uint8 uint32 "
            "vertex_index\r\nend_header\r\n0 0 0\r\n\r\n1 0 0\r\n0 1 0\r\n   \r\n3 2 1 0\r\n"));
  ASSERT_EQ(crlf.F.rows(), 1);
  EXPECT_EQ(crlf.F.row(0), Eigen::RowVector3i(2, 1, 0));
  EXPECT_EQ(crlf.V(1, 0), 1);
  EXPECT_EQ(crlf.V(2, 1), 1);
}

// max_vertices bounds the vertices read, refused from the header's count before any row is read:
// the pyramid's five are read at 5 and refused at 4, ASCII or binary.
TEST_F(PlyFile, MaxVerticesIsALimitThatNamesItself) {
  for (const char* format : {"ascii", "binary_little_endian"}) {
    const std::string file = write(std::string(format) + ".ply", pyramid(format));
    EXPECT_EQ(load_ply(file, 5).V.rows(), 5) << format;
    EXPECT_EQ(test::refusal([&] { load_ply(file, 4); }),
              "load_ply: '" + file +
                  "': 5 vertices, more than the 4 read (max_vertices; --max-vertices raises it)")
        << format;
  }
  EXPECT_NE(test::refusal([&] {
              load_ply(write("zero.ply", pyramid("ascii")), 0);
            }).find("max_vertices must be >= 1"),
            std::string::npos);
}

TEST_F(PlyFile, ABinaryFileReadsAsItsAsciiTwin) {
  const TriangleMesh ascii = load_ply(write("ascii.ply", pyramid("ascii")));
  for (const char* format : {"binary_little_endian", "binary_big_endian"}) {
    const TriangleMesh binary = load_ply(write(std::string(format) + ".ply", pyramid(format)));
    EXPECT_EQ(binary.V, ascii.V) << format;
    EXPECT_EQ(binary.F, ascii.F) << format;
  }
}

TEST_F(PlyFile, APolygonIsFannedFromItsFirstCorner) {
  std::string s =
      "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty "
      "float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (int k = 0; k < 6; ++k)
    s += std::to_string(std::cos(k * M_PI / 3)) + " " + std::to_string(std::sin(k * M_PI / 3)) +
         " 0\n";
  s += "6 5 0 1 2 3 4\n";
  const TriangleMesh mesh = load_ply(write("hexagon.ply", s));
  Eigen::MatrixXi F(4, 3);
  F << 5, 0, 1, 5, 1, 2, 5, 2, 3, 5, 3, 4;
  EXPECT_EQ(mesh.F, F);
}

TEST_F(PlyFile, NormalsAreReadNormalizedOnlyWhenAllThreeArePresent) {
  const std::string body = "0 0 0 0 0 2\n1 0 0 0 3 4\n0 1 0 0 0 0\n3 0 1 2\n";
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty "
      "float z\nproperty float nx\nproperty float ny\nproperty float ";
  const std::string tail = "\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const TriangleMesh with = load_ply(write("normals.ply", head + "nz" + tail + body));
  ASSERT_EQ(with.N.rows(), 3);
  EXPECT_EQ(with.N.row(0), Eigen::RowVector3d(0, 0, 1));
  EXPECT_TRUE(with.N.row(1).isApprox(Eigen::RowVector3d(0, 0.6, 0.8)));
  EXPECT_EQ(with.N.row(2), Eigen::RowVector3d(0, 0, 0));  // a zero normal stays zero
  const TriangleMesh without = load_ply(write("two.ply", head + "w" + tail + body));
  EXPECT_EQ(without.N.rows(), 0);
}

// A vertex's coordinates and normals are numbers: one declared a list is refused naming it (a
// list nx, ny or nz was read as 0 and kept as the normal).
TEST_F(PlyFile, ListCoordinatesOrNormalsAreRefusedNamingTheProperty) {
  auto vertex = [](const std::string& listed) {
    std::string s = "ply\nformat ascii 1.0\nelement vertex 3\n";
    for (const std::string name : {"x", "y", "z", "nx", "ny", "nz"})
      s += (name == listed ? "property list uchar float " : "property float ") + name + "\n";
    return s + "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
           "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
  };
  for (const std::string name : {"x", "z", "nx", "ny", "nz"})
    EXPECT_NE(refusal(name + ".ply", vertex(name))
                  .find("the vertex property '" + name + "' is a list, not a number"),
              std::string::npos)
        << name;
}

TEST_F(PlyFile, RefusesBadHeadersNamingTheFileAndTheLine) {
  const std::string vertex =
      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string face = "element face 1\nproperty list uchar int vertex_indices\n";
  const std::string rows = "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const std::string ascii = "ply\nformat ascii 1.0\n";
  const std::pair<std::string, std::string> cases[] = {
      {"format ascii 1.0\n" + vertex + face + rows, "not a PLY file"},
      {"ply\n" + vertex + face + rows, "the header has no format line"},
      {"ply\nformat ascii 2.0\n" + vertex + face + rows, "header line 2 'format ascii 2.0'"},
      {ascii + vertex + face, "the header has no end_header line"},
      {ascii + "property float x\n" + vertex + face + rows,
       "header line 3 'property float x': a property before any element"},
      {ascii + vertex + "property half w\n" + face + rows, "header line 7 'property half w'"},
      {ascii + vertex + "element face 1\nproperty list float int vertex_indices\n" + rows,
       "unknown list types"},
      {ascii + vertex + "colour 3\n" + face + rows, "unknown keyword 'colour'"},
      // A line's words are read whole: no count '3x' read as 3, no words left over.
      {ascii + "element vertex 3x\nproperty float x\nproperty float y\nproperty float z\n" + face +
           rows,
       "header line 3 'element vertex 3x': expected 'element NAME COUNT'"},
      {ascii + vertex + "element face 1 2\nproperty list uchar int vertex_indices\n" + rows,
       "header line 7 'element face 1 2': expected 'element NAME COUNT'"},
      {ascii + vertex + "property float w extra\n" + face + rows,
       "header line 7 'property float w extra': words after the property's name"},
      {"ply\nformat ascii 1.0 x\n" + vertex + face + rows,
       "header line 2 'format ascii 1.0 x': expected 'format NAME 1.0'"},
      {ascii + "element vertex 3\nproperty float x\nproperty float y\n" + face +
           "end_header\n0 0\n1 0\n0 1\n3 0 1 2\n",
       "the vertex element lacks x, y or z"},
      {ascii + vertex + "end_header\n0 0 0\n1 0 0\n0 1 0\n", "no face element"},
      {ascii + vertex + "element face 1\nproperty int vertex_indices\n" + rows,
       "the face element has no vertex_indices list"},
      {"ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\nproperty "
       "float y\nproperty float z\n" +
           face + "end_header\n" + std::string(40, '\0'),
       "element 'vertex' claims 1000 rows, more than its 40 bytes of data hold"},
      // Control characters of a header line or an element's name are quoted, not sent to the
      // terminal.
      {ascii + vertex + "colour\x1b[31m 3\n" + face + rows,
       "header line 7 'colour\\x1b[31m 3': unknown keyword 'colour\\x1b[31m'"},
      {"ply\nformat binary_little_endian 1.0\nelement junk\x1b[2J 5\n" + vertex + face +
           "end_header\n",
       "element 'junk\\x1b[2J' has 5 rows but no properties"},
  };
  int i = 0;
  for (const auto& [bytes, what] : cases) {
    const std::string message = refusal("bad" + std::to_string(i++) + ".ply", bytes);
    EXPECT_NE(message.find(what), std::string::npos) << what << "\n" << message;
    EXPECT_EQ(message.find('\x1b'), std::string::npos) << message;
  }
}

TEST_F(PlyFile, RefusesBadRowsNamingTheElementAndTheRow) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty "
      "float z\nelement face 2\nproperty list uchar float vertex_indices\nend_header\n0 0 0\n1 0 "
      "0\n0 1 0\n3 0 1 2\n";
  EXPECT_NE(refusal("fraction.ply", head + "3 0 1 1.5\n")
                .find("face 1 of 2: names vertex 1.5, not a whole number"),
            std::string::npos);
  EXPECT_NE(refusal("negative.ply", head + "3 0 -1 2\n").find("face 1 of 2: names vertex -1"),
            std::string::npos);
  EXPECT_NE(refusal("few.ply", head + "3 0 1\n").find("face 1 of 2: has too few values"),
            std::string::npos);
  // A binary list whose signed length is negative.
  std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty uchar x\nproperty uchar "
      "y\nproperty uchar z\nelement face 1\nproperty list char uchar vertex_indices\n"
      "end_header\n";
  binary += std::string("\0\0\0\1\0\0\0\1\0", 9) + "\xff" + std::string("\0\1\2", 3);
  EXPECT_NE(refusal("length.ply", binary).find("face 0 of 1: a list length of -1"),
            std::string::npos);
}

}  // namespace
}  // namespace geolens
