// GeoJSON read and written back: every geometry type and top-level object round-trips exactly,
// ids and properties pass through unchanged, and malformed documents are refused with one line
// naming the document, the feature and the problem.

#include "geolens/io/geojson.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "support/refusal.h"
#include "support/scratch_folder.h"
#include "support/vector_data.h"

namespace geolens {
namespace {

using Json = nlohmann::ordered_json;

// n x 2 coordinates with every bit of their mantissas in use, seeded.
Eigen::MatrixX2d coordinates(int n, unsigned seed, bool closed = false) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-50, 1050);
  Eigen::MatrixX2d P(n, 2);
  for (int i = 0; i < n; ++i) P.row(i) << u(rng), u(rng);
  if (closed) P.row(n - 1) = P.row(0);
  return P;
}

using test::make_geometry;

// Bit for bit: the same types, paths, ring counts and members.
bool same(const Geometry& a, const Geometry& b) {
  if (a.type != b.type || a.rings != b.rings || a.paths.size() != b.paths.size() ||
      a.members.size() != b.members.size())
    return false;
  for (size_t k = 0; k < a.paths.size(); ++k)
    if (a.paths[k].rows() != b.paths[k].rows() ||
        (a.paths[k].size() > 0 &&  // an empty path's data() may be null, which memcmp refuses
         std::memcmp(a.paths[k].data(), b.paths[k].data(),
                     sizeof(double) * size_t(a.paths[k].size())) != 0))
      return false;
  for (size_t k = 0; k < a.members.size(); ++k)
    if (!same(a.members[k], b.members[k])) return false;
  return true;
}

void expect_same(const VectorData& a, const VectorData& b) {
  EXPECT_EQ(a.root, b.root);
  ASSERT_EQ(a.features.size(), b.features.size());
  for (size_t k = 0; k < a.features.size(); ++k) {
    SCOPED_TRACE("feature " + std::to_string(k));
    const Feature &f = a.features[k], &g = b.features[k];
    ASSERT_EQ(f.geometry.has_value(), g.geometry.has_value());
    if (f.geometry) EXPECT_TRUE(same(*f.geometry, *g.geometry));
    EXPECT_EQ(f.id, g.id);
    EXPECT_EQ(f.properties, g.properties);
  }
}

// A feature of every geometry type, a nested collection, empty geometries and a null one.
VectorData every_type() {
  VectorData data;
  unsigned seed = 1;
  auto add = [&](Geometry g) { data.features.push_back({std::move(g), "", "null"}); };
  add(make_geometry(GeometryType::kPoint, {coordinates(1, seed++)}));
  add(make_geometry(GeometryType::kMultiPoint, {coordinates(5, seed++)}));
  add(make_geometry(GeometryType::kMultiPoint, {Eigen::MatrixX2d(0, 2)}));
  add(make_geometry(GeometryType::kLineString, {coordinates(7, seed++)}));
  add(make_geometry(GeometryType::kMultiLineString,
                    {coordinates(2, seed++), coordinates(4, seed++)}));
  add(make_geometry(GeometryType::kPolygon,
                    {coordinates(6, seed++, true), coordinates(4, seed++, true)}));  // with a hole
  add(make_geometry(GeometryType::kPolygon, {}));
  add(make_geometry(
      GeometryType::kMultiPolygon,
      {coordinates(5, seed++, true), coordinates(4, seed++, true), coordinates(8, seed++, true)},
      {2, 1}));
  Geometry inner;
  inner.type = GeometryType::kGeometryCollection;
  inner.members.push_back(make_geometry(GeometryType::kPoint, {coordinates(1, seed++)}));
  Geometry collection;
  collection.type = GeometryType::kGeometryCollection;
  collection.members = {make_geometry(GeometryType::kLineString, {coordinates(3, seed++)}), inner};
  add(collection);
  data.features.push_back({std::nullopt, "\"nowhere\"", "{\"name\":\"no geometry\"}"});
  return data;
}

TEST(GeoJson, EveryGeometryTypeRoundTripsExactly) {
  const VectorData data = every_type();
  ASSERT_EQ(vector_data_problem(data), "");
  const std::string text = geojson_text(data);
  const VectorData back = parse_geojson(text, "every_type");
  expect_same(data, back);
  EXPECT_EQ(geojson_text(back), text);
  // Every type name is in the text, as GeoJSON spells it.
  for (const char* type : {"\"Point\"", "\"MultiPoint\"", "\"LineString\"", "\"MultiLineString\"",
                           "\"Polygon\"", "\"MultiPolygon\"", "\"GeometryCollection\""})
    EXPECT_NE(text.find(type), std::string::npos) << type;
  // A valid GeoJSON document to any JSON reader: one feature per line.
  const Json json = Json::parse(text);
  EXPECT_EQ(json["type"], "FeatureCollection");
  EXPECT_EQ(json["features"].size(), data.features.size());
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), long(data.features.size()) + 2);
}

TEST(GeoJson, TheTopLevelObjectIsKept) {
  const std::string geometry = R"({"type":"LineString","coordinates":[[1.5,2],[3,4.25]]})";
  const VectorData bare = parse_geojson(geometry, "bare");
  EXPECT_EQ(bare.root, GeoJsonRoot::kGeometry);
  ASSERT_EQ(bare.features.size(), 1u);
  EXPECT_EQ(Json::parse(geojson_text(bare)), Json::parse(geometry));

  const std::string feature =
      R"({"type":"Feature","id":"a","geometry":{"type":"Point","coordinates":[1,2]},)"
      R"("properties":{"name":"here"}})";
  const VectorData one = parse_geojson(feature, "one");
  EXPECT_EQ(one.root, GeoJsonRoot::kFeature);
  EXPECT_EQ(Json::parse(geojson_text(one)), Json::parse(feature));

  // A bare geometry left without one is an empty collection, still valid GeoJSON.
  VectorData emptied = bare;
  emptied.features[0].geometry.reset();
  EXPECT_EQ(Json::parse(geojson_text(emptied)),
            Json::parse(R"({"type":"GeometryCollection","geometries":[]})"));
}

TEST(GeoJson, IdsAndPropertiesPassThroughUnchanged) {
  const std::string properties =
      R"({"zeta":1,"name":"Zürich \"Hb\"","alpha":[1,2.5,{"b":null,"a":true}],"big":12345678901234,)"
      R"("x":-0.125,"nested":{"z":"last","a":"first"}})";
  const std::string text = R"({"type":"FeatureCollection","features":[)"
                           R"({"type":"Feature","id":42,"geometry":null,"properties":)" +
                           properties +
                           R"(},{"type":"Feature","id":"s-1","geometry":null,"properties":null},)"
                           R"({"type":"Feature","geometry":null}]})";
  const VectorData data = parse_geojson(text, "properties");
  ASSERT_EQ(data.features.size(), 3u);
  const Json in = Json::parse(properties), out = Json::parse(data.features[0].properties);
  EXPECT_EQ(out, in);
  EXPECT_EQ(out.dump(), in.dump());  // the same keys in the same order
  EXPECT_EQ(data.features[0].id, "42");
  EXPECT_EQ(data.features[1].id, "\"s-1\"");
  EXPECT_EQ(data.features[1].properties, "null");
  EXPECT_EQ(data.features[2].properties, "null");  // absent: written as null
  const Json written = Json::parse(geojson_text(data));
  EXPECT_EQ(written["features"][0]["properties"].dump(), in.dump());
  EXPECT_EQ(written["features"][0]["id"], 42);
  EXPECT_EQ(written["features"][1]["id"], "s-1");
  EXPECT_FALSE(written["features"][2].contains("id"));

  EXPECT_EQ(string_property(data.features[0], "name"), "Zürich \"Hb\"");
  EXPECT_EQ(string_property(data.features[0], "zeta"), std::nullopt);  // not a string
  EXPECT_EQ(string_property(data.features[0], "missing"), std::nullopt);
  EXPECT_EQ(string_property(data.features[1], "name"), std::nullopt);  // properties null
}

// Bad documents: InvalidInput, one line, naming the document, where and what.
TEST(GeoJson, MalformedDocumentsAreRefusedNamingTheProblem) {
  const std::string line = R"({"type":"Feature","geometry":{"type":"LineString","coordinates":)";
  const std::string point = R"({"type":"Feature","geometry":{"type":"Point","coordinates":)";
  auto collection = [](const std::string& feature) {
    return R"({"type":"FeatureCollection","features":[{"type":"Feature","geometry":null},)" +
           feature + "]}";
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{\"type\": \"Feature\",\n \"geometry\": nul}", "line 2"},
      {"", "not JSON"},
      {R"([1, 2])", "expected an object"},
      {R"({"features":[]})", "no \"type\""},
      {R"({"type":"Circle","coordinates":[1,2]})", "unknown geometry type \"Circle\""},
      {R"({"type":"FeatureCollection","features":{}})", "\"features\" is object"},
      {R"({"type":"LineString"})", "no \"coordinates\""},
      {collection(line + R"([[1,2]]},"properties":null})"),
       "feature 1: LineString: path 0 has 1 positions, needs at least 2"},
      {collection(point + R"([1,2,3]},"properties":null})"), "altitude"},
      {collection(point + R"(["1",2]},"properties":null})"),
       "feature 1 Point coordinates: expected a position [x, y]"},
      {collection(point + R"([1e999,2]},"properties":null})"), "not JSON"},
      {collection(line + R"([[1,2],[3,4],5]},"properties":null})"),
       "feature 1 LineString coordinates[2]"},
      {R"({"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,1]]]})", "not closed"},
      {R"({"type":"Polygon","coordinates":[[[0,0],[1,0],[0,0]]]})", "needs at least 4"},
      {R"({"type":"MultiPolygon","coordinates":[[]]})", "polygon 0 has 0 rings"},
      {collection(R"({"type":"Feature","properties":null})"), "feature 1: has no \"geometry\""},
      {collection(R"({"type":"Feature","geometry":null,"properties":"x"})"),
       "feature 1: \"properties\" is string"},
      {collection(R"({"type":"Feature","geometry":null,"id":[1]})"), "\"id\" is array"},
      {collection(R"({"type":"Point","coordinates":[1,2]})"), "feature 1: expected a Feature"},
      {R"({"type":"GeometryCollection","geometries":[{"type":"Point","coordinates":[]}]})",
       "the geometry GeometryCollection geometries[0] Point coordinates"},
  };
  for (const auto& [text, mentions] : cases) {
    SCOPED_TRACE(text);
    try {
      parse_geojson(text, "bad.geojson");
      ADD_FAILURE() << "accepted";
    } catch (const InvalidInput& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("parse_geojson: 'bad.geojson': ", 0), 0u) << what;
      EXPECT_NE(what.find(mentions), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

// Nesting is measured without parsing (brackets in strings do not count) and bounded before the
// readers recurse: 100 000 nested GeometryCollections overflowed the stack; 256 levels are read.
TEST(GeoJson, NestingIsBoundedBeforeParsing) {
  EXPECT_EQ(json_depth("1"), 0u);
  EXPECT_EQ(json_depth(R"({"a": [1, {"b": "[[[{"}], "c\"[": []})"), 3u);
  auto nested = [](size_t n) {
    std::string text;
    for (size_t k = 0; k < n; ++k) text += R"({"type":"GeometryCollection","geometries":[)";
    text += R"({"type":"Point","coordinates":[1,2]})";
    for (size_t k = 0; k < n; ++k) text += "]}";
    return text;
  };
  EXPECT_EQ(json_depth(nested(100)), 202u);
  EXPECT_EQ(parse_geojson(nested(100), "deep.geojson").features.size(), 1u);
  try {
    parse_geojson(nested(100000), "deep.geojson");
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("nested 200002 levels deep; at most 256 are read"),
              std::string::npos)
        << e.what();
  }
}

class GeoJsonFile : public testing::ScratchFolderTest {};

TEST_F(GeoJsonFile, ReadsAFileAndNamesItWhenItCannot) {
  {
    std::ofstream out(path("in.geojson"));
    out << R"({"type":"Point","coordinates":[3,4]})";
  }
  const VectorData data = read_geojson(path("in.geojson"));
  ASSERT_EQ(data.features.size(), 1u);
  EXPECT_EQ(data.features[0].geometry->paths[0], Eigen::RowVector2d(3, 4));
  for (const std::string& bad : {path("missing.geojson"), dir_.string()}) {
    try {
      read_geojson(bad);
      ADD_FAILURE() << bad;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

// A GeoJSON file larger than kMaxGeoJsonBytes is refused by its size before it is read (a 65 MiB
// sparse file, read as zeros it would be 65 MiB of text), and so is such a text however it came.
TEST_F(GeoJsonFile, ALargerFileThanTheBoundIsRefusedUnread) {
  const std::string big = path("big.geojson");
  std::ofstream(big).close();
  std::filesystem::resize_file(big, kMaxGeoJsonBytes + (size_t(1) << 20));
  try {
    read_geojson(big);
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()),
              "read_geojson: '" + big + "' is larger than the 64 MiB a GeoJSON file may hold");
  }
  try {
    parse_geojson(std::string(kMaxGeoJsonBytes + 1, ' '), "standard input");
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()),
              "parse_geojson: 'standard input' is larger than the 64 MiB a GeoJSON text may hold "
              "(16 bytes a position of max_points, at least 64 MiB)");
  }
  // A limit of more points reads a larger file: the 65 MiB of zeros are read, and are not JSON.
  EXPECT_EQ(geojson_bytes_limit(kMaxGeoJsonPoints), kMaxGeoJsonBytes);
  EXPECT_EQ(geojson_bytes_limit(size_t(1) << 23), size_t(128) << 20);
  EXPECT_NE(test::refusal([&] { read_geojson(big, size_t(1) << 23); }).find("not JSON"),
            std::string::npos);
}

// max_points bounds the positions read, in all the features, named in the refusal: the four
// positions below are read at 4 and refused at 3 where the fourth is; the limit is at least 1.
TEST_F(GeoJsonFile, MaxPointsIsALimitThatNamesItself) {
  const std::string file = path("four.geojson");
  std::ofstream(file) << R"({"type":"FeatureCollection","features":[)"
                      << R"({"type":"Feature","properties":null,"geometry":)"
                      << R"({"type":"LineString","coordinates":[[0,0],[1,0],[1,1]]}},)"
                      << R"({"type":"Feature","properties":null,"geometry":)"
                      << R"({"type":"Point","coordinates":[5,5]}}]})";
  EXPECT_EQ(read_geojson(file, 4).features.size(), 2u);
  EXPECT_EQ(test::refusal([&] { read_geojson(file, 3); }),
            "parse_geojson: '" + file +
                "': feature 1 Point coordinates: more than the 3 positions read in all "
                "(max_points; --max-points raises it)");
  EXPECT_NE(test::refusal([&] { read_geojson(file, 0); }).find("max_points must be >= 1"),
            std::string::npos);
}

TEST(GeoJson, WritingRefusesInvalidData) {
  VectorData data;
  data.features.push_back(
      {make_geometry(GeometryType::kLineString, {coordinates(1, 1)}), "", "null"});
  EXPECT_THROW(geojson_text(data), InvalidInput);
  data.features[0].geometry = make_geometry(GeometryType::kPoint, {coordinates(1, 1)});
  data.features[0].properties = "{not json";
  EXPECT_THROW(geojson_text(data), InvalidInput);
  data.features[0].properties = "null";
  data.root = GeoJsonRoot::kFeature;
  data.features.push_back(data.features[0]);  // a single Feature with two
  EXPECT_THROW(geojson_text(data), InvalidInput);
}

}  // namespace
}  // namespace geolens
