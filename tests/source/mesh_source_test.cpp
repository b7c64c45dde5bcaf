// The mesh source: OBJ and PLY readers agree, the camera puts a silhouette where it says, tiles
// are renders of their region at their level's resolution (no seams), a zoom-3 focus is as
// sharp as a direct 3x render, and bad files are refused with one line naming them.

#include "source/mesh_source.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/thread_pool.h"
#include "geolens/core/errors.h"
#include "geolens/render/render.h"
#include "geolens/source/source_file.h"
#include "geolens/warp/warp_mesh.h"
#include "render3d/obj_file.h"
#include "render3d/ply_file.h"
#include "support/refusal.h"
#include "support/scratch_folder.h"

namespace {

using geolens::Image;
using geolens::InvalidInput;
using geolens::MeshRenderer;
using geolens::MeshSourceOptions;
using geolens::MeshStyle;
using geolens::OrbitCamera;
using geolens::PixelRegion;
using geolens::TriangleMesh;

void write(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

/// A cube [-1, 1]^3 with quads, counter-clockwise from outside.
const double kCube[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                            {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
const int kQuads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                          {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};

std::string cube_obj() {
  std::string s = "# cube\no cube\n";
  for (const auto& v : kCube)
    s += "v " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) +
         "\n";
  for (const auto& q : kQuads)
    s += "f " + std::to_string(q[0] + 1) + " " + std::to_string(q[1] + 1) + " " +
         std::to_string(q[2] + 1) + " " + std::to_string(q[3] + 1) + "\n";
  return s;
}

std::string ply_header(const std::string& format, int vertices, int faces) {
  return "ply\nformat " + format + " 1.0\ncomment a cube\nelement vertex " +
         std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
         "element face " +
         std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string cube_ply_ascii() {
  std::string s = ply_header("ascii", 8, 6);
  for (const auto& v : kCube)
    s += std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + " 200\n";
  for (const auto& q : kQuads)
    s += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) +
         " " + std::to_string(q[3]) + "\n";
  return s;
}

template <typename T>
void append(std::string& s, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  s.append(bytes, sizeof(T));
}

std::string cube_ply_binary() {
  std::string s = ply_header("binary_little_endian", 8, 6);
  for (const auto& v : kCube) {
    for (int k = 0; k < 3; ++k) append(s, float(v[k]));
    append(s, uint8_t(200));
  }
  for (const auto& q : kQuads) {
    append(s, uint8_t(4));
    for (int k = 0; k < 4; ++k) append(s, int32_t(q[k]));
  }
  return s;
}

/// The triangles of `mesh` as sets of their corner positions, in their winding from the
/// smallest corner (so a rotation of the corners compares equal, a flip does not).
std::set<std::vector<double>> triangles_of(const TriangleMesh& mesh) {
  std::set<std::vector<double>> out;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    std::vector<std::vector<double>> corners;
    for (int k = 0; k < 3; ++k)
      corners.push_back(
          {mesh.V(mesh.F(f, k), 0), mesh.V(mesh.F(f, k), 1), mesh.V(mesh.F(f, k), 2)});
    const auto first = std::min_element(corners.begin(), corners.end()) - corners.begin();
    std::vector<double> key;
    for (int k = 0; k < 3; ++k) {
      const auto& c = corners[size_t((first + k) % 3)];
      key.insert(key.end(), c.begin(), c.end());
    }
    out.insert(key);
  }
  return out;
}

/// A latitude-longitude sphere of radius 1: rows x cols quads, each split in two triangles.
TriangleMesh uv_sphere(int rows, int cols) {
  TriangleMesh mesh;
  mesh.V.resize((rows + 1) * cols, 3);
  for (int i = 0; i <= rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const double theta = M_PI * i / rows, phi = 2 * M_PI * j / cols;
      mesh.V.row(i * cols + j) << std::sin(theta) * std::cos(phi), std::cos(theta),
          std::sin(theta) * std::sin(phi);
    }
  mesh.F.resize(2 * rows * cols, 3);
  int t = 0;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const int a = i * cols + j, b = i * cols + (j + 1) % cols, c = a + cols, d = b + cols;
      mesh.F.row(t++) << a, b, c;
      mesh.F.row(t++) << b, d, c;
    }
  return mesh;
}

double mean_absolute_difference(const Image& a, const Image& b) {
  EXPECT_EQ(a.pixels.size(), b.pixels.size());
  double sum = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) sum += std::abs(int(a.pixels[i]) - int(b.pixels[i]));
  return sum / double(a.pixels.size());
}

/// Sum of squared differences between horizontal and vertical neighbours, all channels.
double gradient_energy(const Image& image) {
  double sum = 0;
  for (int y = 0; y + 1 < image.height; ++y)
    for (int x = 0; x + 1 < image.width; ++x)
      for (int c = 0; c < image.channels; ++c) {
        const double here = image.at(x, y)[c];
        const double dx = image.at(x + 1, y)[c] - here, dy = image.at(x, y + 1)[c] - here;
        sum += dx * dx + dy * dy;
      }
  return sum;
}

/// The pixels of `region` copied out of a fetched texel region.
Image copy_region(const geolens::TexelRegion& texels) {
  Image out(texels.width, texels.height, texels.channels);
  for (int j = 0; j < texels.height; ++j)
    std::memcpy(out.at(0, j), texels.at(texels.x, texels.y + j),
                size_t(texels.width) * size_t(texels.channels));
  return out;
}

class MeshSourceTest : public geolens::testing::ScratchFolderTest {};

/// Total area and enclosed volume (divergence theorem) of a closed mesh.
std::pair<double, double> area_and_volume(const TriangleMesh& mesh) {
  double area = 0, volume = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)),
                          c = mesh.V.row(mesh.F(f, 2));
    area += (b - a).cross(c - a).norm() / 2;
    volume += a.dot(b.cross(c)) / 6;
  }
  return {area, volume};
}

TEST_F(MeshSourceTest, ObjAndPlyLoadTheSameTriangles) {
  // A tetrahedron of triangles: the same triangles, corner for corner, from all three files.
  const std::string tetra_vertices[] = {"0 0 0", "1 0 0", "0 1 0", "0 0 1"};
  const int tetra[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::string obj = "o tetra\n", ascii = ply_header("ascii", 4, 4),
              binary = ply_header("binary_little_endian", 4, 4);
  for (const std::string& v : tetra_vertices) {
    obj += "v " + v + "\n";
    ascii += v + " 7\n";
    std::istringstream in(v);
    for (float x; in >> x;) append(binary, x);
    append(binary, uint8_t(7));
  }
  for (const auto& t : tetra) {
    obj += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
           std::to_string(t[2] + 1) + "\n";
    ascii += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) +
             "\n";
    append(binary, uint8_t(3));
    for (int k = 0; k < 3; ++k) append(binary, int32_t(t[k]));
  }
  write(path("tetra.obj"), obj);
  write(path("tetra_ascii.ply"), ascii);
  write(path("tetra_binary.ply"), binary);
  const TriangleMesh t_obj = geolens::load_obj(path("tetra.obj"));
  const TriangleMesh t_ascii = geolens::load_ply(path("tetra_ascii.ply"));
  const TriangleMesh t_binary = geolens::load_ply(path("tetra_binary.ply"));
  EXPECT_EQ(t_obj.F.rows(), 4);
  EXPECT_EQ(triangles_of(t_obj), triangles_of(t_ascii));
  EXPECT_EQ(triangles_of(t_ascii), triangles_of(t_binary));
  EXPECT_NEAR(area_and_volume(t_obj).second, 1.0 / 6, 1e-12);  // outward: positive volume

  // A cube of quads: each file's triangulation may pick either diagonal, so compare what does
  // not depend on it: 12 triangles, area 24, volume 8, outward normals.
  write(path("cube.obj"), cube_obj());
  write(path("ascii.ply"), cube_ply_ascii());
  write(path("binary.ply"), cube_ply_binary());
  const TriangleMesh cubes[] = {geolens::load_obj(path("cube.obj")),
                                geolens::load_ply(path("ascii.ply")),
                                geolens::load_ply(path("binary.ply"))};
  EXPECT_EQ(cubes[1].V, cubes[2].V);
  EXPECT_EQ(cubes[1].F, cubes[2].F);
  for (const TriangleMesh& cube : cubes) {
    EXPECT_EQ(cube.F.rows(), 12);
    EXPECT_EQ(cube.N.rows(), 0);  // none in the files: computed when rendered
    const auto [area, volume] = area_and_volume(cube);
    EXPECT_NEAR(area, 24, 1e-9);
    EXPECT_NEAR(volume, 8, 1e-9);
    const Eigen::MatrixXd normals = geolens::face_normals(cube.V, cube.F);
    for (Eigen::Index f = 0; f < cube.F.rows(); ++f) {
      const Eigen::RowVector3d centroid =
          (cube.V.row(cube.F(f, 0)) + cube.V.row(cube.F(f, 1)) + cube.V.row(cube.F(f, 2))) / 3;
      EXPECT_GT(normals.row(f).dot(centroid), 0) << "face " << f;
    }
  }
}

TEST_F(MeshSourceTest, SquareFacingTheCameraCoversTheProjectedRectangle) {
  // A unit square in the z = 0 plane seen from +z: its silhouette is the rectangle the
  // projection gives, |x| <= focal / 2 / distance around the frame's centre.
  TriangleMesh square;
  square.V.resize(4, 3);
  square.V << -0.5, -0.5, 0, 0.5, -0.5, 0, 0.5, 0.5, 0, -0.5, 0.5, 0;
  square.F.resize(2, 3);
  square.F << 0, 1, 2, 0, 2, 3;
  OrbitCamera camera;
  camera.azimuth_degrees = 0;
  camera.elevation_degrees = 0;
  MeshStyle style;
  style.samples = 1;
  style.colour = {0, 0, 0};
  style.specular = 0;
  const int width = 240, height = 160;
  const MeshRenderer renderer(square, camera, width, height, style);
  const geolens::Projection& p = renderer.projection();
  const double distance = (p.eye - Eigen::Vector3d::Zero()).norm();
  const double half = p.focal * 0.5 / distance;  // frame pixels
  EXPECT_NEAR(half * std::sqrt(2.0), height / 2.0 * std::sin(M_PI / 12) / std::tan(M_PI / 12),
              1e-9);  // fitted: the bounding sphere (radius sqrt(1/2)) just fits the height
  const Image image = renderer.render({1, 0, 0, width, height});
  int wrong = 0, covered = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double dx = std::abs(x + 0.5 - width / 2.0), dy = std::abs(y + 0.5 - height / 2.0);
      const bool in = image.at(x, y)[0] < 128;
      covered += in;
      if (dx < half - 1 && dy < half - 1 && !in) ++wrong;
      if ((dx > half + 1 || dy > half + 1) && in) ++wrong;
    }
  EXPECT_EQ(wrong, 0);
  EXPECT_NEAR(covered, 4 * half * half, 4 * 2 * half);  // the area, within a pixel of border
}

TEST_F(MeshSourceTest, TilesAreDirectRendersOfTheirRegionAndJoinWithoutSeams) {
  MeshSourceOptions options;
  options.style.edges = true;
  options.style.shading = geolens::MeshShading::flat;
  options.tiling.tile_size = 64;
  const int width = 96, height = 80;
  const geolens::SourceFile file = geolens::mesh_source(uv_sphere(12, 20), width, height, options);
  EXPECT_EQ(file.kind, "mesh");
  EXPECT_EQ(file.scale, 4);
  EXPECT_EQ(file.source->width(), width * 4);
  EXPECT_EQ(file.source->height(), height * 4);
  EXPECT_EQ(file.source->channels(), 3);
  const MeshRenderer direct(uv_sphere(12, 20), options.camera, width, height, options.style);
  // Level 0 across four tiles (x 100 - 220, y 40 - 160 crosses texel 128 both ways) against the
  // same pixels rendered directly at 4x, and level 1 (2x) likewise.
  for (const int level : {0, 1}) {
    const Image tiles = copy_region(
        file.source->fetch(level, 100 >> level, 40 >> level, 120 >> level, 120 >> level));
    const Image region = direct.render(
        {std::ldexp(1.0, level - 2), 100 >> level, 40 >> level, 120 >> level, 120 >> level});
    EXPECT_EQ(tiles.pixels, region.pixels) << "level " << level;
    // Not a blank picture: the sphere and its edges are there.
    const auto [lo, hi] = std::minmax_element(tiles.pixels.begin(), tiles.pixels.end());
    EXPECT_LT(*lo, 100);
    EXPECT_GT(*hi, 200);
  }
  // Rendering in bands on a pool gives the same pixels as one band.
  geolens::ThreadPool pool(2);
  const PixelRegion whole{0.5, 0, 0, 2 * width, 2 * height};
  EXPECT_EQ(direct.render(whole, &pool).pixels, direct.render(whole).pixels);
  ASSERT_TRUE(file.counters);
  const auto counters = file.counters();
  ASSERT_EQ(counters.size(), 2u);
  EXPECT_EQ(counters[0].first, "tiles_rendered");
  EXPECT_GE(counters[0].second, 4 + 1);
}

TEST_F(MeshSourceTest, ZoomThreeFocusIsAsSharpAsADirectRender) {
  // The focus of a zoom-3 lens is the uniform magnification of its region: a warp mapping the
  // frame's square [64, 128)^2 onto a 192 x 192 output. Through the mesh source (scale 4), the
  // renderer samples the fine levels, which are real renders; magnifying a 1x picture cannot
  // make detail.
  MeshSourceOptions options;
  options.style.edges = true;
  options.style.shading = geolens::MeshShading::flat;
  const int side = 256;
  const geolens::SourceFile file = geolens::mesh_source(uv_sphere(24, 48), side, side, options);
  geolens::WarpMesh warp;
  warp.F.resize(2, 3);
  warp.F << 0, 1, 2, 0, 2, 3;
  warp.source.resize(4, 2);
  warp.source << 64, 64, 128, 64, 128, 128, 64, 128;
  warp.screen.resize(4, 2);
  warp.screen << 0, 0, 192, 0, 192, 192, 0, 192;
  warp.screen_width = warp.screen_height = 192;
  geolens::RenderOptions render_options;
  render_options.width = render_options.height = 192;
  render_options.source_scale = file.scale;
  const Image focus = geolens::render(warp, *file.source, render_options);

  const MeshRenderer direct(uv_sphere(24, 48), options.camera, side, side, options.style);
  const Image at_3x = direct.render({1.0 / 3, 192, 192, 192, 192});
  const Image at_1x = direct.render({1, 0, 0, side, side});
  render_options.source_scale = 1;
  const geolens::SourceFile picture = geolens::image_source(at_1x);
  const Image magnified = geolens::render(warp, *picture.source, render_options);

  const double mad = mean_absolute_difference(focus, at_3x);
  const double mad_picture = mean_absolute_difference(magnified, at_3x);
  const double ratio = gradient_energy(focus) / gradient_energy(magnified);
  const double ratio_direct = gradient_energy(at_3x) / gradient_energy(magnified);
  std::printf(
      "zoom 3: MAD(focus, direct 3x) = %.2f, MAD(magnified 1x, direct 3x) = %.2f; gradient "
      "energy focus / magnified 1x = %.2f (direct 3x / magnified 1x = %.2f)\n",
      mad, mad_picture, ratio, ratio_direct);
  EXPECT_LT(mad, 6.0);  // of 255, per channel (measured 3.9: level blending's smoothing)
  EXPECT_LT(mad, mad_picture / 2);
  EXPECT_GT(ratio, 1.5);
}

TEST_F(MeshSourceTest, OpenSourceTakesMeshFilesWithTheView) {
  write(path("cube.obj"), cube_obj());
  write(path("cube.ply"), cube_ply_binary());
  geolens::SourceFileOptions options;
  options.width = 120;
  options.height = 90;
  options.view = "0,0";
  for (const char* name : {"cube.obj", "cube.ply"}) {
    const geolens::SourceFile file = geolens::open_source(path(name), options);
    EXPECT_EQ(file.kind, "mesh");
    EXPECT_EQ(file.frame_width, 120);
    EXPECT_EQ(file.frame_height, 90);
    // Seen from the front, the cube's face is a square centred in the frame: the corner is
    // background, the centre is not.
    const geolens::TexelRegion all = file.source->fetch(2, 0, 0, 120, 90);
    EXPECT_EQ(all.at(0, 0)[0], 255);
    EXPECT_LT(all.at(60, 45)[0], 255);
  }
  const geolens::SourceFile defaults = geolens::open_source(path("cube.obj"));
  EXPECT_EQ(defaults.frame_width, 1024);
  EXPECT_EQ(defaults.frame_height, 1024);
}

using geolens::test::refusal;

TEST_F(MeshSourceTest, RefusesBadMeshFilesWithOneLineNamingTheFile) {
  auto open = [&](const std::string& name, const std::string& bytes) {
    write(path(name), bytes);
    return refusal([&] { geolens::open_source(path(name)); });
  };
  auto expect = [&](const std::string& message, const std::string& name, const std::string& what) {
    EXPECT_NE(message.find(path(name)), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  };
  expect(open("empty.obj", "# nothing\nv 0 0 0\nv 1 0 0\n"), "empty.obj", "no triangle");
  expect(open("missing.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"), "missing.obj", "vertex 7");
  expect(open("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"), "nan.obj",
         "line 2: vertex coordinate 'nan' is not a finite number");
  expect(open("long.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n"), "long.obj",
         "line 4: face index '99999999999999999999' is out of range");
  expect(open("empty.ply", ply_header("ascii", 0, 0)), "empty.ply", "no triangle");
  expect(open("notply.ply", "plx\n"), "notply.ply", "not a PLY file");
  expect(open("format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n"), "format.ply",
         "header line 2");
  // An ASCII count the file's bytes cannot hold (a character and a separator a value) is
  // refused from the header; one they could, when the lines run out.
  expect(open("short.ply", ply_header("ascii", 8, 6) + "0 0 0 1\n1 1 1 1\n"), "short.ply",
         "element 'vertex' claims 8 rows, more than its 16 bytes of data hold");
  expect(open("ends.ply", ply_header("ascii", 3, 0) + "0 0 0 1\n1 1 1 1\n" + std::string(9, ' ')),
         "ends.ply", "vertex 2 of 3: the file ends");
  std::string truncated = cube_ply_binary();
  truncated.resize(truncated.size() - 10);
  expect(open("truncated.ply", truncated), "truncated.ply", "face 5 of 6: the file ends");
  expect(open("twocorners.ply", ply_header("ascii", 3, 1) + "0 0 0 1\n1 0 0 1\n0 1 0 1\n2 0 1\n"),
         "twocorners.ply", "face 0 of 1: has 2 corners");
  expect(open("index.ply", ply_header("ascii", 3, 1) + "0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 9\n"),
         "index.ply", "names vertex 9");
  expect(open("letters.ply", ply_header("ascii", 3, 1) + "0 0 zero 1\n1 1 1 1\n0 1 0 1\n3 0 1 2\n"),
         "letters.ply", "vertex 0 of 3: has too few values or one that is not a number");
  write(path("cube.obj"), cube_obj());
  geolens::SourceFileOptions bad_view;
  bad_view.view = "30";
  expect(refusal([&] { geolens::open_source(path("cube.obj"), bad_view); }), "cube.obj",
         "is not AZ,EL");
  bad_view.view = "30,95";
  expect(refusal([&] { geolens::open_source(path("cube.obj"), bad_view); }), "cube.obj",
         "(-90, 90)");
  expect(refusal([&] { geolens::open_source(path("nowhere.obj")); }), "nowhere.obj", "load_obj");
}

}  // namespace
