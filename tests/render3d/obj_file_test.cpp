// The OBJ reader on small files written by the test: positions and faces (1-based and relative
// indices) read exactly, polygons triangulated over their own area and winding, normals kept only
// when every corner of a vertex names the same one, textures and materials ignored, and bad files
// refused with InvalidInput naming load_obj and the file.

#include "render3d/obj_file.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <set>
#include <string>

#include "geolens/core/errors.h"
#include "support/refusal.h"
#include "support/scratch_folder.h"

namespace geolens {
namespace {

class ObjFile : public testing::ScratchFolderTest {};

/// Sum of the triangles' vector areas (the cross products / 2): for a planar polygon, its area
/// times its normal by the right-hand rule, whichever way it was split.
Eigen::Vector3d vector_area(const TriangleMesh& mesh) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)),
                          c = mesh.V.row(mesh.F(f, 2));
    sum += (b - a).cross(c - a) / 2;
  }
  return sum;
}

TEST_F(ObjFile, ReadsPositionsExactlyAndFacesAsZeroBasedIndicesIgnoringTextures) {
  const TriangleMesh mesh = load_obj(write("two.obj",
                                           "# two triangles\n"
                                           "v 0 0 0\nv 1.5 0 0\nv 0 2.25 0\nv -3 0.125 7\n"
                                           "f 1 2 3\nf 3 2 4\n"));
  ASSERT_EQ(mesh.V.rows(), 4);
  ASSERT_EQ(mesh.F.rows(), 2);
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1.5, 0, 0, 0, 2.25, 0, -3, 0.125, 7;
  EXPECT_EQ(mesh.V, V);
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 2, 1, 3;
  EXPECT_EQ(mesh.F, F);
  EXPECT_EQ(mesh.N.rows(), 0);  // no vn lines
  // Texture coordinates, groups and a material library that is not there change nothing.
  const TriangleMesh textured =
      load_obj(write("textured.obj",
                     "mtllib nowhere.mtl\nusemtl stone\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                     "vt 0 0\nvt 1 0\nvt 0 1\ng group\ns 1\nf 1/1 2/2 3/3\n"));
  ASSERT_EQ(textured.F.rows(), 1);
  EXPECT_EQ(textured.F.row(0), Eigen::RowVector3i(0, 1, 2));
}

// "f -3 -2 -1" names the last three vertices defined so far; with several objects, every face
// indexes the one vertex list of the file.
TEST_F(ObjFile, RelativeIndicesCountBackAndObjectsShareOneVertexList) {
  const TriangleMesh mesh = load_obj(write("objects.obj",
                                           "o first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"
                                           "o second\nv 5 5 5\nf 2 4 3\n"));
  ASSERT_EQ(mesh.V.rows(), 4);
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 1, 3, 2;
  EXPECT_EQ(mesh.F, F);
}

// A quad becomes two triangles and a convex pentagon three, covering the polygon once with its
// winding: the vector area is the polygon's area along its right-hand normal.
TEST_F(ObjFile, PolygonsAreTriangulatedOverTheirAreaWithTheirWinding) {
  const TriangleMesh quad =
      load_obj(write("quad.obj", "v 0 0 0\nv 2 0 0\nv 2 3 0\nv 0 3 0\nf 1 2 3 4\n"));
  ASSERT_EQ(quad.F.rows(), 2);
  EXPECT_TRUE(vector_area(quad).isApprox(Eigen::Vector3d(0, 0, 6), 1e-12)) << vector_area(quad);
  std::set<int> used(quad.F.data(), quad.F.data() + quad.F.size());
  EXPECT_EQ(used, (std::set<int>{0, 1, 2, 3}));

  // A regular pentagon in the x = 0 plane, wound clockwise seen from +x: normal -x.
  std::string text;
  for (int k = 0; k < 5; ++k)
    text += "v 0 " + std::to_string(std::cos(-2 * M_PI * k / 5)) + " " +
            std::to_string(std::sin(-2 * M_PI * k / 5)) + "\n";
  text += "f 1 2 3 4 5\n";
  const TriangleMesh pentagon = load_obj(write("pentagon.obj", text));
  ASSERT_EQ(pentagon.F.rows(), 3);
  const double area = 5.0 / 2 * std::sin(2 * M_PI / 5);  // of the unit-circumradius pentagon
  EXPECT_NEAR(vector_area(pentagon).x(), -area, 1e-5);
  EXPECT_NEAR(vector_area(pentagon).tail<2>().norm(), 0, 1e-5);
  for (Eigen::Index f = 0; f < pentagon.F.rows(); ++f) {  // each wound as the pentagon
    const Eigen::Vector3d a = pentagon.V.row(pentagon.F(f, 0)),
                          b = pentagon.V.row(pentagon.F(f, 1)),
                          c = pentagon.V.row(pentagon.F(f, 2));
    EXPECT_LT((b - a).cross(c - a).x(), 0) << "triangle " << f;
  }
}

TEST_F(ObjFile, NormalsAreKeptNormalizedOnlyWhenEveryCornerOfAVertexAgrees) {
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 2\nvn 0 3 4\n";
  const TriangleMesh agree =
      load_obj(write("agree.obj", vertices + "f 1//1 2//1 3//2\nf 2//1 4//1 3//2\n"));
  ASSERT_EQ(agree.N.rows(), 4);
  EXPECT_TRUE(agree.N.row(0).isApprox(Eigen::RowVector3d(0, 0, 1)));
  EXPECT_TRUE(agree.N.row(2).isApprox(Eigen::RowVector3d(0, 0.6, 0.8)));
  // Vertex 2 (index 1) names normal 1 in one face and normal 2 in the other: all are dropped.
  const TriangleMesh differ =
      load_obj(write("differ.obj", vertices + "f 1//1 2//1 3//2\nf 2//2 4//1 3//2\n"));
  EXPECT_EQ(differ.N.rows(), 0);
  // A face without normals drops them too.
  const TriangleMesh partial =
      load_obj(write("partial.obj", vertices + "f 1//1 2//1 3//2\nf 2 4 3\n"));
  EXPECT_EQ(partial.N.rows(), 0);
}

TEST_F(ObjFile, RefusesBadFilesNamingTheReaderAndTheFile) {
  auto expect_refused = [&](const std::string& name, const std::string& text,
                            const std::string& what) {
    const std::string file = write(name, text);
    const std::string message = test::refusal([&] { load_obj(file); });
    EXPECT_EQ(message.rfind("load_obj", 0), 0u) << name << ": " << message;
    EXPECT_NE(message.find(file), std::string::npos) << name << ": " << message;
    EXPECT_NE(message.find(what), std::string::npos) << name << ": " << message;
  };
  expect_refused("noface.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no triangle");
  expect_refused("missing.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "vertex 4");
  expect_refused("infinite.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n",
                 "line 2: vertex coordinate '1e999' is not a finite number");
  expect_refused("word.obj", "v 0 0 0\nv one 0 0\nv 0 1 0\nf 1 2 3\n", "line 2");
  expect_refused("flat.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n",
                 "line 2: a vertex has 2 coordinates, 3 needed");
  expect_refused("empty.obj", "", "");
  const std::string nowhere = path("nowhere.obj");
  const std::string message = test::refusal([&] { load_obj(nowhere); });
  EXPECT_NE(message.find(nowhere), std::string::npos) << message;
}

// max_vertices bounds the vertices read, named in the refusal with the line of the first vertex
// over it, before tinyobjloader holds them: four are read at 4 and refused at 3.
TEST_F(ObjFile, MaxVerticesIsALimitThatNamesItself) {
  const std::string file =
      write("four.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 3 2 4\n");
  EXPECT_EQ(load_obj(file, 4).V.rows(), 4);
  EXPECT_EQ(test::refusal([&] { load_obj(file, 3); }),
            "load_obj: '" + file +
                "': line 4: 4 vertices, more than the 3 read (max_vertices; --max-vertices raises "
                "it)");
  EXPECT_NE(test::refusal([&] { load_obj(file, 0); }).find("max_vertices must be >= 1"),
            std::string::npos);
  EXPECT_EQ(mesh_bytes_limit(kMaxMeshVertices), size_t(512) << 20);
  EXPECT_EQ(mesh_bytes_limit(size_t(1) << 23), size_t(1) << 30);
}

}  // namespace
}  // namespace geolens
