// Vector data through a lens: forward then inverse is the identity, a densified line bends where
// it crosses the lens and stays put beyond its footprint, what lies outside the image is dropped
// or cut as documented, and ids and properties pass through.

#include "geolens/warp/map_features.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/io/geojson.h"
#include "geolens/lens/geometric_lens.h"
#include "lens/focus_lens.h"
#include "support/vector_data.h"
#include "warp/densify.h"

namespace geolens {
namespace {

constexpr double kWidth = 1024, kHeight = 768;
const Eigen::Vector2d kCentre(480, 400);
constexpr double kRadius = 70, kZoom = 2;

// The default (focus) lens: a circle magnified kZoom times, nothing moving beyond its footprint.
const LensResult& lens() {
  static const LensResult result =
      GeometricLens(kWidth, kHeight).solve({Lens{Region::circle(kCentre, kRadius), kZoom}});
  return result;
}

Eigen::MatrixX2d path(std::initializer_list<std::pair<double, double>> points) {
  Eigen::MatrixX2d P(Eigen::Index(points.size()), 2);
  Eigen::Index i = 0;
  for (const auto& [x, y] : points) P.row(i++) << x, y;
  return P;
}

using test::make_geometry;

Feature feature(Geometry g, std::string properties = "null") {
  return {std::move(g), "", std::move(properties)};
}

// Features of every kind, all inside the image, some through the lens.
VectorData inside_features() {
  VectorData data;
  data.features = {
      feature(make_geometry(GeometryType::kPoint, {path({{kCentre.x() + 20, kCentre.y() - 30}})})),
      feature(
          make_geometry(GeometryType::kMultiPoint, {path({{10, 10}, {500, 420}, {1000, 700}})})),
      feature(make_geometry(GeometryType::kLineString, {path({{100, 380}, {900, 420}})})),
      feature(make_geometry(
          GeometryType::kMultiLineString,
          {path({{400, 300}, {560, 500}}), path({{480, 100}, {480, 700}, {20, 700}})})),
      feature(make_geometry(GeometryType::kPolygon,
                            {path({{420, 340}, {540, 340}, {540, 460}, {420, 460}, {420, 340}}),
                             path({{470, 390}, {490, 390}, {490, 410}, {470, 390}})})),
      feature(make_geometry(GeometryType::kMultiPolygon,
                            {path({{300, 300}, {350, 300}, {350, 350}, {300, 300}}),
                             path({{600, 450}, {700, 450}, {650, 560}, {600, 450}})},
                            {1, 1})),
  };
  Geometry collection;
  collection.type = GeometryType::kGeometryCollection;
  collection.members = {make_geometry(GeometryType::kPoint, {path({{470, 410}})}),
                        make_geometry(GeometryType::kLineString, {path({{440, 360}, {520, 440}})})};
  data.features.push_back(feature(collection));
  return data;
}

// Every path of g and its members, in order.
void all_paths(const Geometry& g, std::vector<Eigen::MatrixX2d>& out) {
  for (const Eigen::MatrixX2d& P : g.paths) out.push_back(P);
  for (const Geometry& m : g.members) all_paths(m, out);
}

std::vector<Eigen::MatrixX2d> all_paths(const VectorData& data) {
  std::vector<Eigen::MatrixX2d> out;
  for (const Feature& f : data.features)
    if (f.geometry) all_paths(*f.geometry, out);
  return out;
}

TEST(MapFeatures, ForwardThenInverseIsTheIdentity) {
  const WarpMap map(lens().warp);
  const VectorData data = inside_features();
  const MappedFeatures there = map_features(data, map, {MapDirection::kForward, 2.0});
  EXPECT_FALSE(there.losses.any());
  // Back without densifying again, so every vertex has its counterpart.
  const MappedFeatures back = map_features(
      there.data, map, {MapDirection::kInverse, std::numeric_limits<double>::infinity()});
  EXPECT_FALSE(back.losses.any());
  const std::vector<Eigen::MatrixX2d> original = all_paths(data), mapped = all_paths(there.data),
                                      returned = all_paths(back.data);
  ASSERT_EQ(returned.size(), original.size());
  double worst = 0;
  int vertices = 0;
  for (size_t k = 0; k < original.size(); ++k) {
    // Points are not densified; lines and rings were, at 2 px.
    const bool points = original[k].rows() == mapped[k].rows();
    const Eigen::MatrixX2d expected = points ? original[k] : densify(original[k], 2.0);
    ASSERT_EQ(returned[k].rows(), expected.rows()) << k;
    worst = std::max(worst, (returned[k] - expected).rowwise().norm().maxCoeff());
    vertices += int(expected.rows());
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(vertices, 1000);
  // The lens moved them: the round trip is not trivially the identity.
  EXPECT_GT((mapped[0] - original[0]).norm(), 10);
}

TEST(MapFeatures, ADensifiedLineBendsThroughTheLensAndStaysPutBeyondItsFootprint) {
  const WarpMap map(lens().warp);
  // A straight line passing 30 px below the lens centre, from far left to far right.
  const double y = kCentre.y() + 30;
  const Eigen::MatrixX2d line = path({{20, y}, {1000, y}});
  const double footprint = kRadius * footprint_ratio(Lens{Region::circle(kCentre, kRadius), kZoom});
  ASSERT_GT(kCentre.x() - 20, footprint + 10);  // both ends beyond the footprint
  ASSERT_GT(1000 - kCentre.x(), footprint + 10);
  VectorData data;
  data.features = {feature(make_geometry(GeometryType::kLineString, {line}))};

  const MappedFeatures bent = map_features(data, map, {MapDirection::kForward, 1.0});
  const Eigen::MatrixX2d out = bent.data.features[0].geometry->paths[0];
  const Eigen::MatrixX2d dense = densify(line, 1.0);
  ASSERT_EQ(out.rows(), dense.rows());
  // Every vertex is the mesh's image of its densified source vertex.
  for (Eigen::Index i = 0; i < out.rows(); ++i)
    ASSERT_EQ(Eigen::Vector2d(out.row(i).transpose()), *map.forward(dense.row(i).transpose()));
  // The ends, beyond the footprint, do not move.
  EXPECT_LT((out.row(0) - line.row(0)).norm(), 1e-9);
  EXPECT_LT((out.row(out.rows() - 1) - line.row(1)).norm(), 1e-9);
  // The middle bends away from the straight segment between the ends (the focus pushes it out).
  double furthest = 0;
  for (Eigen::Index i = 0; i < out.rows(); ++i) furthest = std::max(furthest, out(i, 1) - y);
  EXPECT_GT(furthest, 20);
  Eigen::Index middle = 0;
  (dense.col(0).array() - kCentre.x()).abs().minCoeff(&middle);
  EXPECT_GT(out(middle, 1) - y, 20) << "the vertex under the lens centre";
  // Vertices alone would keep it straight: that is what densifying is for.
  const MappedFeatures straight =
      map_features(data, map, {MapDirection::kForward, std::numeric_limits<double>::infinity()});
  EXPECT_EQ(straight.data.features[0].geometry->paths[0].rows(), 2);
}

TEST(MapFeatures, OutsideTheImageIsDroppedOrCutAsDocumented) {
  const WarpMap map(lens().warp);
  VectorData data;
  data.features = {
      // 0: a Point outside: the geometry becomes null, the properties stay.
      feature(make_geometry(GeometryType::kPoint, {path({{-5, 10}})}), R"({"name":"gone"})"),
      // 1: a MultiPoint keeps the points inside.
      feature(make_geometry(GeometryType::kMultiPoint, {path({{10, 10}, {2000, 10}, {20, 30}})})),
      // 2: a line leaving the image at y = 0 and coming back: two pieces, ending on the border.
      feature(make_geometry(GeometryType::kLineString,
                            {path({{100, 50}, {100, -50}, {200, -50}, {200, 50}})})),
      // 3: a polygon partly outside is dropped whole; one inside is kept.
      feature(make_geometry(GeometryType::kMultiPolygon,
                            {path({{-10, 100}, {50, 100}, {50, 150}, {-10, 100}}),
                             path({{100, 100}, {150, 100}, {150, 150}, {100, 100}})},
                            {1, 1})),
      // 4: a line wholly outside is dropped.
      feature(make_geometry(GeometryType::kLineString, {path({{-100, -100}, {-50, -50}})})),
  };
  Geometry collection;
  collection.type = GeometryType::kGeometryCollection;
  collection.members = {make_geometry(GeometryType::kPoint, {path({{-1, -1}})}),
                        make_geometry(GeometryType::kPoint, {path({{3, 4}})})};
  data.features.push_back(feature(collection));  // 5: the member outside is removed
  const MappedFeatures m = map_features(data, map, {MapDirection::kForward, 4.0});
  const std::vector<Feature>& f = m.data.features;
  ASSERT_EQ(f.size(), data.features.size());
  EXPECT_FALSE(f[0].geometry.has_value());
  EXPECT_EQ(f[0].properties, R"({"name":"gone"})");
  EXPECT_EQ(f[1].geometry->paths[0].rows(), 2);
  ASSERT_EQ(f[2].geometry->type, GeometryType::kMultiLineString);
  ASSERT_EQ(f[2].geometry->paths.size(), 2u);
  const Eigen::MatrixX2d &first = f[2].geometry->paths[0], &second = f[2].geometry->paths[1];
  EXPECT_NEAR(first(first.rows() - 1, 1), 0, 1e-6);  // ends on the image's top edge
  EXPECT_NEAR(first(first.rows() - 1, 0), 100, 1e-6);
  EXPECT_NEAR(second(0, 1), 0, 1e-6);  // and starts on it again
  EXPECT_NEAR(second(0, 0), 200, 1e-6);
  EXPECT_EQ(f[3].geometry->rings, std::vector<int>{1});
  EXPECT_NEAR(f[3].geometry->paths[0](0, 0), 100, 1e-9);
  EXPECT_FALSE(f[4].geometry.has_value());
  ASSERT_EQ(f[5].geometry->members.size(), 1u);
  EXPECT_LT((f[5].geometry->members[0].paths[0] - path({{3, 4}})).norm(), 1e-9);
  EXPECT_EQ(m.losses.points, 3);
  EXPECT_EQ(m.losses.lines, 2);
  EXPECT_EQ(m.losses.polygons, 1);
  EXPECT_EQ(vector_data_problem(m.data), "");

  // Empty geometries have nothing to map: null too.
  VectorData empty;
  empty.features = {feature(make_geometry(GeometryType::kMultiPoint, {Eigen::MatrixX2d(0, 2)})),
                    feature(make_geometry(GeometryType::kPolygon, {})),
                    feature(make_geometry(GeometryType::kMultiLineString, {}))};
  for (const Feature& e : map_features(empty, map).data.features)
    EXPECT_FALSE(e.geometry.has_value());

  // A bare geometry left with nothing is written as an empty GeometryCollection.
  VectorData bare;
  bare.root = GeoJsonRoot::kGeometry;
  bare.features = {feature(make_geometry(GeometryType::kPoint, {path({{-5, -5}})}))};
  EXPECT_EQ(geojson_text(map_features(bare, map).data),
            "{\"type\":\"GeometryCollection\",\"geometries\":[]}\n");
}

// A line to a point far outside (x = 1e300) is cut where it leaves the image, as the same line to
// a point just outside is, and counted lost once; the vertices make no work beyond the image.
TEST(MapFeatures, ALineFarBeyondTheImageIsCutAtItsBorder) {
  const WarpMap map(lens().warp);
  auto mapped = [&](double x) {
    VectorData data;
    data.features = {
        feature(make_geometry(GeometryType::kLineString, {path({{100, 50}, {300, 60}, {x, 70}})}))};
    return map_features(data, map, {MapDirection::kForward, 0.5});
  };
  const MappedFeatures far = mapped(1e300), near = mapped(2000);
  EXPECT_EQ(far.losses.lines, 1);
  ASSERT_TRUE(far.data.features[0].geometry.has_value());
  const Eigen::MatrixX2d& cut = far.data.features[0].geometry->paths[0];
  EXPECT_NEAR(cut(cut.rows() - 1, 0), kWidth, 1e-6);  // ends on the right side
  EXPECT_NEAR(cut(0, 0), 100, 1e-9);
  EXPECT_NEAR(cut(0, 1), 50, 1e-9);
  // Up to where it leaves, the line to 1e300 is the segment to (300, 60) then a line of slope
  // 1e-298: nearly horizontal, as densified as the near one over the image's width.
  EXPECT_NEAR(cut(cut.rows() - 1, 1), 60, 1e-6);
  EXPECT_LT(cut.rows(), 2 * near.data.features[0].geometry->paths[0].rows());
}

// The lines' vertices in all are bounded, the option named: 15 million took 1.9 GB.
TEST(MapFeatures, TooManyDensifiedVerticesAreRefusedNamingMaxSegment) {
  VectorData data;
  for (int k = 0; k < 50; ++k)
    data.features.push_back(feature(
        make_geometry(GeometryType::kLineString, {path({{10, 10.0 + k}, {1010, 10.0 + k}})})));
  try {
    map_features(data, WarpMap(lens().warp), {MapDirection::kForward, 0.01});  // 5 million
    ADD_FAILURE();
  } catch (const InvalidOption& e) {
    EXPECT_EQ(e.option, "max_segment");
    EXPECT_NE(e.problem.find("more than 4194304 vertices"), std::string::npos) << e.what();
  }
}

TEST(MapFeatures, IdsAndPropertiesPassThrough) {
  const VectorData data = parse_geojson(
      R"({"type":"FeatureCollection","features":[{"type":"Feature","id":"r1","geometry":)"
      R"({"type":"LineString","coordinates":[[400,400],[560,400]]},"properties":{"z":1,"a":[2]}}]})",
      "properties");
  const MappedFeatures m = map_features(data, WarpMap(lens().warp));
  EXPECT_EQ(m.data.features[0].id, "\"r1\"");
  EXPECT_EQ(m.data.features[0].properties, R"({"z":1,"a":[2]})");
}

TEST(MapFeatures, RefusesBadInputNamingIt) {
  const WarpMap map(lens().warp);
  const VectorData data = inside_features();
  for (const double bad : {0.0, -2.0, std::numeric_limits<double>::quiet_NaN()})
    EXPECT_THROW(map_features(data, map, {MapDirection::kForward, bad}), InvalidInput);
  VectorData open = data;
  open.features[4].geometry->paths[0](4, 0) = 0;
  try {
    map_features(open, map);
    ADD_FAILURE();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(
        std::string(e.what()).rfind("map_features: feature 4: Polygon: ring 0 is not closed", 0),
        0u)
        << e.what();
  }
}

TEST(MapPoints, DropsTheRowsOutsideWithTheirColumnsAndMapsBothWays) {
  const WarpMap map(lens().warp);
  PointTable table;
  table.header = "x,y,id";
  table.points = path({{500, 410}, {-1, 5}, {1000, 700}, {kCentre.x(), kCentre.y()}});
  table.rest = {",a", ",b", ",c", ",d"};
  const MappedPoints there = map_points(table, map, MapDirection::kForward);
  EXPECT_EQ(there.losses.points, 1);
  EXPECT_EQ(there.table.header, "x,y,id");
  EXPECT_EQ(there.table.rest, (std::vector<std::string>{",a", ",c", ",d"}));
  ASSERT_EQ(there.table.points.rows(), 3);
  EXPECT_EQ(Eigen::Vector2d(there.table.points.row(0).transpose()),
            *map.forward(Eigen::Vector2d(500, 410)));
  const MappedPoints back = map_points(there.table, map, MapDirection::kInverse);
  EXPECT_EQ(back.losses.points, 0);
  EXPECT_LT((back.table.points.row(0) - table.points.row(0)).norm(), 1e-6);
  EXPECT_LT((back.table.points.row(2) - table.points.row(3)).norm(), 1e-6);
  table.rest.pop_back();
  EXPECT_THROW(map_points(table, map, MapDirection::kForward), InvalidInput);
}

}  // namespace
}  // namespace geolens
