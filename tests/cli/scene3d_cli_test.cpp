// `geolens magnify` on a mesh (OBJ) and a volume (NRRD) through the real binary: the frame from
// --size, the camera from --view, the transfer from --transfer, the source's numbers in --stats,
// and one-line refusals with exit 2 and nothing written for bad 3D files and options.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "geolens/io/image.h"
#include "support/cli_test.h"

namespace geolens {
namespace {

using testing::CliRun;

class Scene3dCli : public testing::CliTest {
 protected:
  void write(const std::string& name, const std::string& bytes) const {
    std::ofstream(path(name), std::ios::binary) << bytes;
  }
  nlohmann::json stats() const {
    std::ifstream in(path("stats.json"));
    return nlohmann::json::parse(in);
  }
  /// A cube [-1, 1]^3 of quads.
  void write_cube() const {
    write("cube.obj",
          "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
          "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 2 3 7 6\nf 1 5 8 4\n");
  }
  /// A 16^3 int16 NRRD: 1000 inside a sphere of radius 6 voxels, -1000 outside.
  void write_sphere() const {
    std::string data;
    for (int k = 0; k < 16; ++k)
      for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) {
          const double r =
              std::sqrt((i - 7.5) * (i - 7.5) + (j - 7.5) * (j - 7.5) + (k - 7.5) * (k - 7.5));
          const int16_t v = r < 6 ? 1000 : -1000;
          data.append(reinterpret_cast<const char*>(&v), 2);
        }
    write("sphere.nrrd",
          "NRRD0004\ntype: short\ndimension: 3\nsizes: 16 16 16\nencoding: raw\n"
          "endian: little\n\n" +
              data);
  }
};

TEST_F(Scene3dCli, MagnifiesAMeshSeenFromTheView) {
  write_cube();
  const CliRun r = run("magnify " + path("cube.obj") +
                       " --view 0,0 --size 200x160 --lens circle:150,80,25:2 -o " +
                       path("out.png") + " --stats " + path("stats.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const Image out = load_image(path("out.png"));
  EXPECT_EQ(out.width, 200);
  EXPECT_EQ(out.height, 160);
  // Seen from the front, the cube is a grey square around the centre on white.
  EXPECT_LT(out.at(100, 80)[0], 250);
  EXPECT_EQ(out.at(3, 3)[0], 255);
  const nlohmann::json source = stats().at("source");
  EXPECT_EQ(source.at("kind"), "mesh");
  EXPECT_EQ(source.at("scale"), 4.0);
  EXPECT_GE(source.at("tiles_rendered").get<double>(), 1);
}

TEST_F(Scene3dCli, MagnifiesAVolumeThroughTheCtPreset) {
  write_sphere();
  const CliRun r = run("magnify " + path("sphere.nrrd") +
                       " --transfer ct --view 30,20 --size 120x120 --lens circle:60,60,20:2 -o " +
                       path("out.png") + " --stats " + path("stats.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const Image out = load_image(path("out.png"));
  EXPECT_EQ(out.width, 120);
  EXPECT_GT(out.at(60, 60)[0], 100);  // bone: bright
  EXPECT_EQ(out.at(2, 2)[0], 0);      // the black background
  EXPECT_EQ(stats().at("source").at("kind"), "volume");
}

TEST_F(Scene3dCli, RefusesBad3dInputsInOneLine) {
  write_cube();
  write_sphere();
  write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  write("empty.obj", "v 0 0 0\n");
  write("short.nrrd",
        "NRRD0004\ntype: short\ndimension: 3\nsizes: 10 10 10\nencoding: raw\nendian: "
        "little\n\n0123456789");
  write("zero.nrrd",
        "NRRD0004\ntype: short\ndimension: 3\nsizes: 10 0 10\nencoding: raw\nendian: little\n\n");
  const std::string lens = " --lens circle:50,50,20 -o " + path("out.png");
  expect_refused("magnify " + path("bad.obj") + lens, "face 0 names vertex 9 of 3");
  expect_refused("magnify " + path("empty.obj") + lens, "the mesh has no triangle");
  expect_refused("magnify " + path("short.nrrd") + lens,
                 "the header claims 10 x 10 x 10 int16 voxels (2000 bytes), the data holds 10");
  expect_refused("magnify " + path("zero.nrrd") + lens, "a volume of zero size");
  expect_refused("magnify " + path("sphere.nrrd") + " --transfer bone" + lens,
                 "unknown transfer 'bone'");
  expect_refused("magnify " + path("cube.obj") + " --view 10" + lens, "is not AZ,EL");
  // Element counts the data cannot hold are refused before a row is read (a PLY with an element
  // of 10^18 rows and no properties hung; one claiming 2^31 vertices allocated them first).
  const std::string ply = "ply\nformat binary_little_endian 1.0\n";
  write("rows.ply", ply +
                        "element vertex 3\nproperty float x\nproperty float y\nproperty float "
                        "z\nelement junk 1000000000000000000\nelement face 1\nproperty list "
                        "uchar int vertex_indices\nend_header\n" +
                        std::string(49, '\0'));
  expect_refused("magnify " + path("rows.ply") + lens,
                 "element 'junk' has 1000000000000000000 rows but no properties");
  write("many.ply", ply +
                        "element vertex 2147483647\nproperty float x\nproperty float y\nproperty "
                        "float z\nelement face 1\nproperty list uchar int "
                        "vertex_indices\nend_header\n" +
                        std::string(49, '\0'));
  expect_refused("magnify " + path("many.ply") + lens,
                 "element 'vertex' claims 2147483647 rows, more than its 49 bytes of data hold");
  // A header claiming more voxels than are read is refused before anything is allocated.
  write("huge.nrrd",
        "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 65536 65536 3\nencoding: gzip\n\nxx");
  expect_refused("magnify " + path("huge.nrrd") + lens,
                 "sizes: 65536 65536 3): 12884901888 voxels, more than the 268435456 read "
                 "(max_voxels; --max-voxels raises it)");
  // A mesh's vertices are bounded the same way: the cube's 8 are refused at --max-vertices 7
  // (naming the line of the 8th) and read at 8.
  write_cube();
  expect_refused(
      "magnify " + path("cube.obj") + lens + " --max-vertices 7",
      "line 8: 8 vertices, more than the 7 read (max_vertices; --max-vertices raises it)");
  EXPECT_EQ(run("magnify " + path("cube.obj") + lens + " --max-vertices 8").code, 0);
  for (const char* bad : {"0", "-5", "0.5", "1e30"})
    expect_refused("magnify " + path("cube.obj") + lens + " --max-vertices " + bad,
                   "--max-vertices: must be");
  // The limit is an option: a 4 x 4 x 4 volume is refused at --max-voxels 63 and read at 64.
  write("cube.nrrd", "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n" +
                         std::string(64, '\x40'));
  expect_refused("magnify " + path("cube.nrrd") + lens + " --max-voxels 63",
                 "64 voxels, more than the 63 read (max_voxels; --max-voxels raises it)");
  EXPECT_EQ(run("magnify " + path("cube.nrrd") + lens + " --max-voxels 64").code, 0);
  for (const char* bad : {"0", "-5", "0.5", "1e30"})
    expect_refused("magnify " + path("cube.nrrd") + lens + " --max-voxels " + bad,
                   "--max-voxels: must be");
  // A detached data file is an input: an output naming it is refused before any work (it was
  // overwritten).
  write("head.nrrd",
        "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 4 4 4\nencoding: raw\ndata file: "
        "head.raw\n");
  write("head.raw", std::string(64, '\x40'));
  expect_refused("magnify " + path("head.nrrd") + " --lens circle:50,50,20 -o " + path("head.png") +
                     " --stats " + path("head.raw"),
                 "--stats: '" + path("head.raw") + "' would overwrite part of the input '" +
                     path("head.nrrd") + "' '" + path("head.raw") + "'");
}

}  // namespace
}  // namespace geolens
