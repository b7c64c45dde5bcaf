// The vector data model's checks: every shape documented at Geometry is accepted, each broken
// one named.

#include "geolens/io/vector_data.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "support/vector_data.h"

namespace geolens {
namespace {

Eigen::MatrixX2d square(double side) {
  Eigen::MatrixX2d P(5, 2);
  P << 0, 0, side, 0, side, side, 0, side, 0, 0;
  return P;
}

using test::make_geometry;

TEST(VectorData, ValidGeometriesHaveNoProblem) {
  const Eigen::MatrixX2d point = Eigen::RowVector2d(1, 2), line = Eigen::MatrixX2d::Ones(2, 2);
  Geometry collection;
  collection.type = GeometryType::kGeometryCollection;
  collection.members = {make_geometry(GeometryType::kPoint, {point}), collection};
  for (const Geometry& g :
       {make_geometry(GeometryType::kPoint, {point}),
        make_geometry(GeometryType::kMultiPoint, {line}),
        make_geometry(GeometryType::kMultiPoint, {Eigen::MatrixX2d(0, 2)}),
        make_geometry(GeometryType::kLineString, {line}),
        make_geometry(GeometryType::kMultiLineString, {}),
        make_geometry(GeometryType::kMultiLineString, {line, line}),
        make_geometry(GeometryType::kPolygon, {square(4), square(1)}),
        make_geometry(GeometryType::kPolygon, {}),
        make_geometry(GeometryType::kMultiPolygon, {square(4), square(1), square(2)}, {2, 1}),
        collection})
    EXPECT_EQ(geometry_problem(g), "") << to_string(g.type);
}

TEST(VectorData, EachBrokenShapeIsNamed) {
  Eigen::MatrixX2d open = square(3);
  open(4, 0) = 1;
  Eigen::MatrixX2d not_finite = Eigen::MatrixX2d::Ones(3, 2);
  not_finite(2, 1) = std::numeric_limits<double>::infinity();
  Geometry member_broken;
  member_broken.type = GeometryType::kGeometryCollection;
  member_broken.members = {make_geometry(GeometryType::kLineString, {Eigen::RowVector2d(1, 1)})};
  Geometry point_with_members = make_geometry(GeometryType::kPoint, {Eigen::RowVector2d(1, 1)});
  point_with_members.members = {point_with_members};
  const std::vector<std::pair<Geometry, std::string>> cases = {
      {make_geometry(GeometryType::kPoint, {}), "Point: needs one path of one position"},
      {make_geometry(GeometryType::kPoint, {Eigen::MatrixX2d::Ones(2, 2)}),
       "Point: needs one path"},
      {make_geometry(GeometryType::kMultiPoint, {not_finite}),
       "MultiPoint: path 0 row 2 is not finite"},
      {make_geometry(GeometryType::kLineString, {Eigen::RowVector2d(1, 1)}),
       "LineString: path 0 has 1 positions, needs at least 2"},
      {make_geometry(GeometryType::kMultiLineString, {not_finite, Eigen::RowVector2d(1, 1)}),
       "MultiLineString: line 0 row 2 is not finite"},
      {make_geometry(GeometryType::kPolygon, {square(2), open}), "Polygon: ring 1 is not closed"},
      {make_geometry(GeometryType::kMultiPolygon, {square(2), open}, {1, 1}),
       "MultiPolygon: polygon 1: ring 0 is not closed"},
      {make_geometry(GeometryType::kMultiPolygon, {square(2)}, {2}),
       "ring counts sum to 2 but it has 1"},
      {make_geometry(GeometryType::kMultiPolygon, {square(2)}, {1, 0}), "polygon 1 has 0 rings"},
      {make_geometry(GeometryType::kPolygon, {square(2)}, {1}), "Polygon: has ring counts"},
      {point_with_members, "Point: has members"},
      {member_broken, "GeometryCollection: member 0: LineString: path 0 has 1 positions"},
  };
  for (const auto& [g, mentions] : cases) {
    const std::string problem = geometry_problem(g);
    EXPECT_NE(problem.find(mentions), std::string::npos) << problem << " / " << mentions;
  }
  VectorData data;
  data.features = {{make_geometry(GeometryType::kPoint, {Eigen::RowVector2d(1, 1)}), "", "null"},
                   {std::nullopt, "", "null"},
                   {make_geometry(GeometryType::kPolygon, {open}), "", "null"}};
  EXPECT_EQ(vector_data_problem(data).rfind("feature 2: Polygon: ring 0 is not closed", 0), 0u);
  data.features.pop_back();
  EXPECT_EQ(vector_data_problem(data), "");
  data.root = GeoJsonRoot::kFeature;
  EXPECT_NE(vector_data_problem(data), "");  // a single Feature holding two
}

}  // namespace
}  // namespace geolens
