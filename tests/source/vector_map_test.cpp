// The vector map: projection and framing, fills where the data says, the style file's schema and
// its refusals, layers by zoom, and the labels: rank by local scale, no overlaps, nothing drawn
// outside the output or outside the labels' boxes; and no seam where a lens changes the level.

#include "source/vector_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/io/geojson.h"
#include "geolens/lens/classic_lens.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens_spec.h"
#include "geolens/render/render.h"
#include "geolens/source/map_style.h"
#include "geolens/warp/warp_map.h"
#include "geolens/warp/warp_mesh.h"
#include "source/map_labels.h"
#include "support/scratch_folder.h"

using geolens::Image;
using geolens::InvalidInput;
using geolens::MapLabel;
using geolens::PlacedLabel;
using geolens::SourceFile;
using geolens::SourceFileOptions;
using geolens::TexelRegion;
using geolens::WarpMap;
using geolens::WarpMesh;

namespace {

using VectorMapTest = geolens::testing::ScratchFolderTest;

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

Image render_frame(const SourceFile& file) {
  geolens::RenderOptions options;
  options.width = file.frame_width;
  options.height = file.frame_height;
  options.source_scale = file.scale;
  options.threads = 1;
  return geolens::render(geolens::identity_warp(file.frame_width, file.frame_height), *file.source,
                         options);
}

bool is(const uint8_t* p, int r, int g, int b, int tolerance = 8) {
  return std::abs(p[0] - r) <= tolerance && std::abs(p[1] - g) <= tolerance &&
         std::abs(p[2] - b) <= tolerance;
}

/// A 10 x 10 degree square at lon [0, 10], lat [0, 10], with a 2 x 2 hole at [4, 6].
const char* kSquare = R"({"type": "FeatureCollection", "features": [
  {"type": "Feature", "properties": {"kind": "land"}, "geometry": {"type": "Polygon",
   "coordinates": [[[0, 0], [10, 0], [10, 10], [0, 10], [0, 0]],
                   [[4, 4], [6, 4], [6, 6], [4, 6], [4, 4]]]}},
  {"type": "Feature", "properties": {"kind": "road"}, "geometry": {"type": "LineString",
   "coordinates": [[-5, -5], [15, -5]]}}]})";

/// Plate carree, [-10, -10] to [20, 20] framed 300 x 300: 10 px per degree, north up.
const char* kSquareStyle = R"({"background": "#0000ff", "projection": "plate_carree",
  "extent": [-10, -10, 20, 20],
  "layers": [{"where": {"kind": "land"}, "fill": "#ff0000"},
             {"where": {"kind": ["road"]}, "stroke": "#00ff00", "width": 3, "min_zoom": 4}]})";

TEST_F(VectorMapTest, PolygonFillsWhereItsCoordinatesSay) {
  write_text(path("square.geojson"), kSquare);
  write_text(path("style.json"), kSquareStyle);
  SourceFileOptions options;
  options.width = 300;
  options.style = path("style.json");
  const SourceFile file = geolens::open_source(path("square.geojson"), options);
  EXPECT_EQ(file.kind, "vector map");
  ASSERT_EQ(file.frame_width, 300);
  ASSERT_EQ(file.frame_height, 300);
  EXPECT_EQ(file.scale, 8.0);
  // The square is x [100, 200] (lon 0 - 10), y [100, 200] (lat 10 - 0); its hole x, y [140, 160].
  const Image frame = render_frame(file);
  for (auto [x, y] : {std::pair{103, 103}, {196, 103}, {103, 196}, {196, 196}, {130, 150}})
    EXPECT_TRUE(is(frame.at(x, y), 255, 0, 0)) << x << ", " << y;
  for (auto [x, y] : {std::pair{97, 150}, {203, 150}, {150, 97}, {150, 203}, {150, 150}, {20, 20}})
    EXPECT_TRUE(is(frame.at(x, y), 0, 0, 255)) << x << ", " << y;
}

// Coordinates a hair past the valid range, as real files have them (Natural Earth's land:
// 180.00000000000014, -90.00000000000003), are read as the range's end; farther ones are refused
// with the value as written, not rounded to one that looks valid.
TEST_F(VectorMapTest, CoordinatesWithinABillionthOfADegreeOfTheRangeAreClamped) {
  auto feature = [](const std::string& position) {
    return R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {},
      "geometry": {"type": "LineString", "coordinates": [[0, 0], )" +
           position + "]}}]}";
  };
  write_text(path("style.json"),
             R"({"projection": "plate_carree", "layers": [{"stroke": "#000"}]})");
  SourceFileOptions options;
  options.width = 200;
  options.style = path("style.json");
  write_text(path("edge.geojson"), feature("[180.00000000000014, -90.00000000000003]"));
  EXPECT_EQ(geolens::open_source(path("edge.geojson"), options).frame_width, 200);
  write_text(path("past.geojson"), feature("[180.000001, 0]"));
  try {
    geolens::open_source(path("past.geojson"), options);
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("the position (180.000001, 0) is not a longitude"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(VectorMapTest, LayerShowsOnlyOnTheLevelsOfItsZooms) {
  const geolens::VectorData data = geolens::parse_geojson(kSquare, "square");
  const SourceFile file =
      geolens::vector_map_source(data, geolens::parse_map_style(kSquareStyle, "style"), 300);
  // The road, lat -5 at y = 250, is drawn on levels of zoom >= 4 (levels 0, 1), not on level 3.
  auto green_texels = [&](int level) {
    const double s = 8.0 / (1 << level);
    const TexelRegion r =
        file.source->fetch(level, int(120 * s), int(245 * s), int(20 * s), int(10 * s));
    int n = 0;
    for (int y = r.y; y < r.y + r.height; ++y)
      for (int x = r.x; x < r.x + r.width; ++x) n += is(r.at(x, y), 0, 255, 0, 40);
    return n;
  };
  EXPECT_GT(green_texels(0), 0);
  EXPECT_GT(green_texels(1), 0);
  EXPECT_EQ(green_texels(2), 0);
  EXPECT_EQ(green_texels(3), 0);
}

TEST_F(VectorMapTest, LayerDrawsOnlyItsGeometry) {
  // A layer of lines, selecting every feature: the road (y = 250) is drawn, the square's
  // outline (x = 100) is not.
  const SourceFile file = geolens::vector_map_source(
      geolens::parse_geojson(kSquare, "square"),
      geolens::parse_map_style(R"({"background": "#0000ff", "projection": "plate_carree",
        "extent": [-10, -10, 20, 20], "layers": [{"geometry": "line", "stroke": "#00ff00",
        "fill": "#ff0000", "width": 8}]})",
                               "style"),
      300);
  const Image frame = render_frame(file);
  EXPECT_TRUE(is(frame.at(150, 250), 0, 255, 0, 40));
  EXPECT_TRUE(is(frame.at(100, 150), 0, 0, 255));
  EXPECT_TRUE(is(frame.at(150, 150), 0, 0, 255));
}

TEST_F(VectorMapTest, WebMercatorStretchesLatitudesAndSizeFollowsTheAspect) {
  const geolens::VectorData data = geolens::parse_geojson(
      R"({"type": "MultiPoint", "coordinates": [[0, 0], [60, 60]]})", "points");
  const SourceFile file = geolens::vector_map_source(data, geolens::default_map_style(), 1000);
  const double pi = 3.14159265358979323846;
  const double y60 = std::log(std::tan(pi / 4 + pi / 6));  // 1.317
  EXPECT_EQ(file.frame_width, 1000);
  EXPECT_EQ(file.frame_height, std::lround(1000 * y60 / (pi / 3)));
  // The default width without a size.
  EXPECT_EQ(geolens::vector_map_source(data, geolens::default_map_style()).frame_width, 1024);
}

TEST_F(VectorMapTest, BothSidesGivenTheMapIsCentredNotStretched) {
  const SourceFile file =
      geolens::vector_map_source(geolens::parse_geojson(kSquare, "square"),
                                 geolens::parse_map_style(kSquareStyle, "style"), 300, 600);
  ASSERT_EQ(file.frame_height, 600);
  // 10 px per degree both ways, the 300 x 300 extent centred: the square at x [100, 200],
  // y [250, 350].
  const Image frame = render_frame(file);
  for (auto [x, y] : {std::pair{103, 253}, {196, 253}, {103, 346}, {196, 346}})
    EXPECT_TRUE(is(frame.at(x, y), 255, 0, 0)) << x << ", " << y;
  for (auto [x, y] : {std::pair{150, 246}, {150, 354}, {97, 300}, {203, 300}})
    EXPECT_TRUE(is(frame.at(x, y), 0, 0, 255)) << x << ", " << y;
}

// A side set from the extent's aspect is checked before it becomes an int: a line 3.7e-6 degrees
// high at a height of 16000 asks for a width of about 4.3e9 pixels (was taken as 8046, wrapped),
// and the refusal names that width (was a wrapped 1072110565 for a line 1e-9 high).
TEST_F(VectorMapTest, AFrameSideTooLargeForAnIntIsRefusedNamingItsSize) {
  const geolens::MapStyle plate =
      geolens::parse_map_style(R"({"projection": "plate_carree"})", "style");
  for (const double high : {3.7252833e-6, 1e-9}) {
    const geolens::VectorData line =
        geolens::parse_geojson(R"({"type": "LineString", "coordinates": [[0, 0], [1, )" +
                                   geolens::number_text(high) + "]]}",
                               "line");
    try {
      const SourceFile file = geolens::vector_map_source(line, plate, 0, 16000);
      ADD_FAILURE() << "accepted as " << file.frame_width << " x " << file.frame_height;
    } catch (const InvalidInput& e) {
      const std::string frame =
          "a frame of " + geolens::number_text(std::round(16000 / high)) + " x 16000 pixels";
      EXPECT_NE(std::string(e.what()).find(frame), std::string::npos) << e.what();
    }
  }
}

// The map's frame places degrees where the map draws them (the square's corners of the centred
// 300 x 600 frame above), and tells pixels back in degrees, in both projections.
TEST_F(VectorMapTest, ItsFramePlacesDegreesWhereItDrawsThemAndBack) {
  const SourceFile plate =
      geolens::vector_map_source(geolens::parse_geojson(kSquare, "square"),
                                 geolens::parse_map_style(kSquareStyle, "style"), 300, 600);
  ASSERT_TRUE(plate.map_frame.has_value());
  const geolens::MapFrame& frame = *plate.map_frame;
  EXPECT_LT((frame.pixels(0, 10) - Eigen::Vector2d(100, 250)).norm(), 1e-9);
  EXPECT_LT((frame.pixels(10, 0) - Eigen::Vector2d(200, 350)).norm(), 1e-9);
  const geolens::VectorData europe =
      geolens::read_geojson(GEOLENS_SOURCE_DIR "/examples/europe.geojson");
  const SourceFile mercator = geolens::vector_map_source(europe, geolens::default_map_style(), 800);
  ASSERT_TRUE(mercator.map_frame.has_value());
  for (const geolens::SourceFile* file : {&plate, &mercator})
    for (double lon = -30; lon <= 40; lon += 7)
      for (double lat = -60; lat <= 80; lat += 9) {
        const Eigen::Vector2d back = file->map_frame->degrees(file->map_frame->pixels(lon, lat));
        EXPECT_NEAR(back.x(), lon, 1e-9);
        EXPECT_NEAR(back.y(), lat, 1e-9);
      }
  // A labelled place of the map is drawn where its degrees say (Paris: 2.35 E, 48.86 N, the
  // label anchored at the place's dot).
  const std::vector<MapLabel> labels =
      geolens::vector_map_labels(europe, geolens::default_map_style(), 800);
  size_t checked = 0;
  for (const geolens::Feature& f : europe.features) {
    if (!f.geometry || f.geometry->type != geolens::GeometryType::kPoint) continue;
    const Eigen::Vector2d at =
        mercator.map_frame->pixels(f.geometry->paths[0](0, 0), f.geometry->paths[0](0, 1));
    for (const MapLabel& label : labels)
      if ((label.position - at).norm() < 1e-9) ++checked;
  }
  EXPECT_GT(checked, 10u);
  // Pixels are no degrees: a GeoJSON in pixels placed on the map is refused naming it.
  const geolens::VectorData pixels =
      geolens::parse_geojson(R"({"type": "Point", "coordinates": [400, 300]})", "pixels");
  try {
    geolens::to_frame_pixels(pixels, frame, "pixels.geojson");
    ADD_FAILURE();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("'pixels.geojson': feature 0: the position (400, 300)"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(VectorMapTest, RendersTheSameOnSeveralThreads) {
  const std::string examples = std::string(GEOLENS_SOURCE_DIR) + "/examples/";
  SourceFileOptions options;
  options.width = 300;
  options.style = examples + "europe_style.json";
  const SourceFile a = geolens::open_vector_map(examples + "europe.geojson", options);
  const SourceFile b = geolens::open_vector_map(examples + "europe.geojson", options);
  // A zoom-2 view of the middle, so that finer levels than the frame's are drawn too.
  WarpMesh zoom = geolens::identity_warp(a.frame_width, a.frame_height);
  zoom.screen *= 2;
  zoom.screen.rowwise() -= Eigen::RowVector2d(a.frame_width / 2.0, a.frame_height / 2.0);
  geolens::RenderOptions render_options;
  render_options.width = a.frame_width;
  render_options.height = a.frame_height;
  render_options.source_scale = a.scale;
  render_options.threads = 1;
  const Image one = geolens::render(zoom, *a.source, render_options);
  render_options.threads = 4;
  const Image four = geolens::render(zoom, *b.source, render_options);
  EXPECT_TRUE(one.pixels == four.pixels);
}

TEST_F(VectorMapTest, BadStyleIsRefusedNamingTheFileAndTheKey) {
  write_text(path("square.geojson"), kSquare);
  auto refusal = [&](const std::string& style) {
    write_text(path("style.json"), style);
    SourceFileOptions options;
    options.style = path("style.json");
    try {
      geolens::open_vector_map(path("square.geojson"), options);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("not refused");
  };
  auto expect_names = [&](const std::string& what, const std::string& key) {
    EXPECT_NE(what.find(path("style.json")), std::string::npos) << what;
    EXPECT_NE(what.find(key), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  };
  expect_names(refusal(R"({"layers": [{"fill": "#ff0000"}, {"fill": "#12"}]})"), "layers[1].fill");
  expect_names(refusal(R"({"layers": [{"fill": "red"}]})"), "'red' is not a colour");
  expect_names(refusal(R"({"layers": [{"colour": "#ff0000"}]})"), "layers[0].colour: unknown key");
  expect_names(refusal(R"({"backgrund": "#ffffff"})"), "backgrund: unknown key");
  expect_names(refusal(R"({"layers": [{"label": {"size": "big"}}]})"), "layers[0].label.size");
  expect_names(refusal(R"({"layers": [{"min_zoom": 4, "max_zoom": 2}]})"), "min_zoom");
  expect_names(refusal(R"({"projection": "lambert"})"), "projection");
  expect_names(refusal(R"({"layers": [{"geometry": "curve"}]})"), "layers[0].geometry");
  expect_names(refusal(R"({"extent": [10, 0, 5, 20]})"), "extent");
  expect_names(refusal("{\"layers\": [\n{\"fill\": }]}"), "line 2");
  // Sizes a renderer would spend without bound on (a point radius of 1e300 hung it).
  expect_names(refusal(R"({"layers": [{"radius": 1e300}]})"), "layers[0].radius: 1e+300");
  expect_names(refusal(R"({"layers": [{"width": 5000}]})"), "at most 1000");
  // A number past a double is the file's fault too, named with it (it exited 1 with the JSON
  // library's text alone).
  expect_names(refusal(R"({"layers": [{"width": 1e999}]})"), "number overflow parsing '1e999'");
  // A malformed GeoJSON names its file and the element.
  write_text(path("bad.geojson"), R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": null, "geometry": {"type": "Point", "coordinates": [1]}}]})");
  try {
    geolens::open_source(path("bad.geojson"));
    FAIL() << "not refused";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(path("bad.geojson")), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("feature 0"), std::string::npos) << e.what();
  }
  // Pixels are not degrees: a latitude of 300 is refused, naming the feature and the position.
  write_text(path("pixels.geojson"), R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": null, "geometry": {"type": "Point", "coordinates": [1, 2]}},
    {"type": "Feature", "properties": null, "geometry": {"type": "Point",
     "coordinates": [120, 300]}}]})");
  try {
    geolens::open_source(path("pixels.geojson"));
    FAIL() << "not refused";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path("pixels.geojson")), std::string::npos) << what;
    EXPECT_NE(what.find("feature 1: the position (120, 300)"), std::string::npos) << what;
  }
}

/// Labels of rank 0 - 5 on a grid of `n` x `n` points over a width x height frame, base 2.
std::vector<MapLabel> grid_labels(int n, double width, double height) {
  std::vector<MapLabel> labels;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      MapLabel l;
      l.position = {(i + 0.5) * width / n, (j + 0.5) * height / n};
      l.text = "P" + std::to_string(j * n + i);
      l.rank = (i * 7 + j * 3) % 6;
      l.style.base = 2;
      l.style.size = 10;
      labels.push_back(l);
    }
  return labels;
}

/// The identity on a width x height frame, magnified `zoom` times onto a zoom * width x
/// zoom * height output.
WarpMap uniform_zoom(int width, int height, double zoom) {
  WarpMesh mesh = geolens::identity_warp(width, height);
  mesh.screen *= zoom;
  mesh.screen_width = int(width * zoom);
  mesh.screen_height = int(height * zoom);
  return WarpMap(mesh);
}

double max_rank(const std::vector<MapLabel>& labels, const std::vector<PlacedLabel>& placed) {
  double r = -1;
  for (const PlacedLabel& p : placed) r = std::max(r, labels[p.index].rank);
  return r;
}

TEST_F(VectorMapTest, ZoomShowsLabelsOfHigherRank) {
  const std::vector<MapLabel> labels = grid_labels(8, 400, 400);
  const auto at1 = geolens::place_labels(labels, uniform_zoom(400, 400, 1), 400, 400);
  const auto at2 = geolens::place_labels(labels, uniform_zoom(400, 400, 2), 800, 800);
  const auto at4 = geolens::place_labels(labels, uniform_zoom(400, 400, 4), 1600, 1600);
  ASSERT_FALSE(at1.empty());
  EXPECT_EQ(max_rank(labels, at1), 2);  // base: ranks <= 2 at zoom 1
  EXPECT_EQ(max_rank(labels, at2), 3);
  EXPECT_EQ(max_rank(labels, at4), 4);
  EXPECT_GT(at2.size(), at1.size());
  EXPECT_GT(at4.size(), at2.size());
  // A label of a layer shown from zoom 2 on: only at zoom 2 and above, whatever its rank.
  std::vector<MapLabel> late(1, labels[0]);
  late[0].rank = 0;
  late[0].min_zoom = 2;
  EXPECT_TRUE(geolens::place_labels(late, uniform_zoom(400, 400, 1), 400, 400).empty());
  EXPECT_EQ(geolens::place_labels(late, uniform_zoom(400, 400, 2), 800, 800).size(), 1u);
  for (const PlacedLabel& p : at2) {
    EXPECT_NEAR(p.scale, 2, 1e-9);
    // At its point's mapped position: its box touches the point's side at `offset` + halo.
    const Eigen::Vector2d expected = 2 * labels[p.index].position;
    EXPECT_NEAR(p.anchor.x(), expected.x(), 1e-9);
    EXPECT_NEAR(p.anchor.y(), expected.y(), 1e-9);
  }
}

TEST_F(VectorMapTest, PlacedLabelsDoNotOverlapAndStayInsideTheOutput) {
  // Far too many labels for the room, some at the very edges.
  std::vector<MapLabel> labels = grid_labels(20, 300, 200);
  for (MapLabel& l : labels) l.style.base = 10;
  for (double x : {0.0, 299.9}) {
    MapLabel l;
    l.position = {x, 100};
    l.text = "Edge";
    l.rank = -1;
    labels.push_back(l);
  }
  const auto placed = geolens::place_labels(labels, uniform_zoom(300, 200, 1), 300, 200);
  ASSERT_GT(placed.size(), 10u);
  EXPECT_LT(placed.size(), labels.size());
  int edges = 0;
  for (size_t a = 0; a < placed.size(); ++a) {
    const PlacedLabel& p = placed[a];
    EXPECT_GE(p.x0, 0);
    EXPECT_GE(p.y0, 0);
    EXPECT_LE(p.x1, 300);
    EXPECT_LE(p.y1, 200);
    EXPECT_GT(p.x1 - p.x0, 5);
    edges += labels[p.index].text == "Edge";
    for (size_t b = a + 1; b < placed.size(); ++b) {
      const PlacedLabel& q = placed[b];
      EXPECT_FALSE(p.x0 < q.x1 && q.x0 < p.x1 && p.y0 < q.y1 && q.y0 < p.y1)
          << labels[p.index].text << " overlaps " << labels[q.index].text;
    }
  }
  EXPECT_EQ(edges, 2);  // moved to the side that fits, not dropped nor cut

  // Drawing changes pixels only inside the placed boxes, and some inside them.
  Image image(300, 200, 3, 200);
  const Image before = image;
  geolens::draw_labels(image, labels, placed);
  int changed_inside = 0;
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 300; ++x) {
      const bool changed = !std::equal(image.at(x, y), image.at(x, y) + 3, before.at(x, y));
      bool inside = false;
      for (const PlacedLabel& p : placed)
        inside = inside || (x + 1 > p.x0 && x < p.x1 && y + 1 > p.y0 && y < p.y1);
      if (changed && !inside) ADD_FAILURE() << "pixel " << x << ", " << y << " outside the boxes";
      changed_inside += changed && inside;
    }
  EXPECT_GT(changed_inside, 100);
}

TEST_F(VectorMapTest, OverlayDrawsTheDotsAndLabelsOfALabelledLayerUnmagnified) {
  write_text(path("places.geojson"), R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {"name": "Alpha", "scalerank": 0},
     "geometry": {"type": "Point", "coordinates": [0, 0]}},
    {"type": "Feature", "properties": {"name": "Beta", "scalerank": 1},
     "geometry": {"type": "Point", "coordinates": [10, 5]}},
    {"type": "Feature", "properties": {"name": "Gamma", "scalerank": 9},
     "geometry": {"type": "Point", "coordinates": [5, 10]}}]})");
  write_text(path("style.json"), R"({"extent": [-20, -20, 30, 30], "layers": [
    {"radius": 3, "fill": "#000000", "label": {"text": "name", "base": 3}}]})");
  SourceFileOptions options;
  options.width = 400;
  options.style = path("style.json");
  const SourceFile file = geolens::open_source(path("places.geojson"), options);
  ASSERT_TRUE(file.overlay);
  const std::vector<MapLabel> points =
      geolens::vector_map_labels(geolens::read_geojson(path("places.geojson")),
                                 geolens::read_map_style(path("style.json")), 400);
  ASSERT_EQ(points.size(), 3u);

  // Magnified 2x: the frame onto an output twice its size.
  const int width = 2 * file.frame_width, height = 2 * file.frame_height;
  WarpMesh zoom = geolens::identity_warp(file.frame_width, file.frame_height);
  zoom.screen *= 2;
  zoom.screen_width = width;
  zoom.screen_height = height;
  geolens::RenderOptions render_options;
  render_options.width = width;
  render_options.height = height;
  render_options.source_scale = file.scale;
  Image output = geolens::render(zoom, *file.source, render_options);
  const Image plain = output;
  file.overlay(output, geolens::framed_warp_map(zoom, width, height));
  for (const MapLabel& point : points) {
    const Eigen::Vector2d at = 2 * point.position;
    const int x = int(at.x()), y = int(at.y());
    // The texture has no dot (the background), the overlay a black one of 3 screen pixels, not
    // magnified: 5 pixels above its centre is still the background.
    EXPECT_FALSE(is(plain.at(x, y), 0, 0, 0, 60)) << point.text;
    EXPECT_TRUE(is(output.at(x, y), 0, 0, 0, 60)) << point.text;
    EXPECT_TRUE(std::equal(output.at(x, y - 5), output.at(x, y - 5) + 3, plain.at(x, y - 5)))
        << point.text;
  }
  double labels = -1;
  for (const auto& [name, value] : file.counters())
    if (name == "labels") labels = value;
  EXPECT_EQ(labels, 2);  // Alpha and Beta; Gamma's rank 9 needs a scale of 2^6
}

TEST_F(VectorMapTest, ALensOverEuropeShowsNamesTheMapWithoutItLeavesOut) {
  // The example map (Natural Earth, examples/europe.geojson) framed 1024 x 977, a zoom-4 lens
  // over the Low Countries, as docs/sources.md shows.
  const std::string examples = std::string(GEOLENS_SOURCE_DIR) + "/examples/";
  const geolens::VectorData data = geolens::read_geojson(examples + "europe.geojson");
  const geolens::MapStyle style = geolens::read_map_style(examples + "europe_style.json");
  const std::vector<MapLabel> labels = geolens::vector_map_labels(data, style, 1024, 977);
  ASSERT_GT(labels.size(), 500u);

  const auto names = [&](const std::vector<PlacedLabel>& placed) {
    std::set<std::string> n;
    for (const PlacedLabel& p : placed) n.insert(labels[p.index].text);
    return n;
  };
  const std::set<std::string> plain = names(geolens::place_labels(
      labels, geolens::framed_warp_map(geolens::identity_warp(1024, 977), 1024, 977), 1024, 977));
  const geolens::GeometricLens lens(1024, 977);
  const geolens::LensResult result = lens.solve(geolens::parse_lens_spec(
      "circle:378,420,70:4", 2, geolens::Profile::kGaussian, 0, 1024, 977));
  const WarpMap map = geolens::framed_warp_map(result.warp, 1024, 977);
  const std::vector<PlacedLabel> placed = geolens::place_labels(labels, map, 1024, 977);

  // Names shown in the focus (within the lens's magnified region, around its centre on screen)
  // that the map without the lens shows nowhere.
  const Eigen::Vector2d centre = *map.forward({378, 420});
  std::vector<std::string> revealed;
  for (const PlacedLabel& p : placed)
    if ((p.anchor - centre).norm() < 70 * 4 && !plain.count(labels[p.index].text))
      revealed.push_back(labels[p.index].text);
  std::string list;
  for (const std::string& name : revealed) list += name + " ";
  EXPECT_GE(revealed.size(), 4u) << list;  // measured: Rotterdam Antwerpen Lille Cologne Luxembourg
  for (const std::string& name : {"Rotterdam", "Antwerpen"})
    EXPECT_NE(std::find(revealed.begin(), revealed.end(), name), revealed.end()) << name;
  EXPECT_EQ(plain.count("Amsterdam"), 1u);
}

/// The level of detail render() picks for each pixel of a width x height render of `warp`, row
/// by row, as render.cpp's set_up computes it: log2 of the largest singular value of the Jacobian
/// of the screen triangle that holds the pixel's centre, in level-0 texels (source_scale per
/// source pixel) per output pixel, clamped to [0, levels - 1]; NaN outside the mesh.
std::vector<double> pixel_lods(const WarpMesh& warp, double source_scale, int levels, int width,
                               int height) {
  const WarpMap map = geolens::framed_warp_map(warp, width, height);
  const WarpMesh& mesh = map.mesh();
  std::vector<double> triangle_lods(size_t(mesh.F.rows()), std::nan(""));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    Eigen::Matrix2d screen, source;
    for (int k = 0; k < 2; ++k) {
      screen.col(k) =
          (mesh.screen.row(mesh.F(f, k + 1)) - mesh.screen.row(mesh.F(f, 0))).transpose();
      source.col(k) =
          (mesh.source.row(mesh.F(f, k + 1)) - mesh.source.row(mesh.F(f, 0))).transpose();
    }
    if (std::abs(screen.determinant()) < 1e-9) continue;
    const Eigen::Matrix2d J = source_scale * source * screen.inverse();
    const double sigma = 0.5 * (std::hypot(J(0, 0) + J(1, 1), J(1, 0) - J(0, 1)) +
                                std::hypot(J(0, 0) - J(1, 1), J(1, 0) + J(0, 1)));
    triangle_lods[size_t(f)] = sigma > 1 ? std::min(std::log2(sigma), double(levels - 1)) : 0.0;
  }
  std::vector<double> lods(size_t(width) * size_t(height), std::nan(""));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Eigen::Index f = map.screen_triangle({x + 0.5, y + 0.5});
      if (f >= 0) lods[size_t(y) * size_t(width) + size_t(x)] = triangle_lods[size_t(f)];
    }
  return lods;
}

/// How much more neighbouring pixels differ where render() changes level than the same pixels
/// differ where it does not. `a` and `b` are one warp rendered from two pyramids of one map whose
/// levels are `shift` (about 1/2) apart: b's level of detail is a's, `lods`, plus shift, so a
/// pixel where a changes level is about mid-level in b. The pairs of horizontally or vertically
/// neighbouring pixels in the lens's transition ring (level of detail neither `focus_lod` nor
/// `context_lod`) whose level of detail crosses a midpoint m + 1/2 between two levels of a: their
/// summed absolute difference in a over the same in b; and the same with a and b swapped, for the
/// midpoints of b. `seam` is the geometric mean of the two: above 1 where a change of level shows
/// as a step, and not biased by one map's levels showing more detail than the other's (which
/// raises one ratio about as much as it lowers the other).
struct SeamRatio {
  double a_over_b = 0, b_over_a = 0, seam = 0;
  int a_pairs = 0, b_pairs = 0;
};
SeamRatio seam_ratio(const Image& a, const Image& b, const std::vector<double>& lods, double shift,
                     double focus_lod, double context_lod) {
  auto in_ring = [&](double lod) {
    return std::isfinite(lod) && std::abs(lod - focus_lod) > 1e-6 &&
           std::abs(lod - context_lod) > 1e-6;
  };
  auto difference = [](const Image& image, int x, int y, int dx, int dy) {
    int d = 0;
    for (int c = 0; c < image.channels; ++c)
      d += std::abs(image.at(x, y)[c] - image.at(x + dx, y + dy)[c]);
    return double(d);
  };
  SeamRatio r;
  double a_at_a = 0, b_at_a = 0, a_at_b = 0, b_at_b = 0;  // summed differences at a's, b's seams
  for (int y = 0; y + 1 < a.height; ++y)
    for (int x = 0; x + 1 < a.width; ++x)
      for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
        const double p = lods[size_t(y) * size_t(a.width) + size_t(x)];
        const double q = lods[size_t(y + dy) * size_t(a.width) + size_t(x + dx)];
        if (!in_ring(p) || !in_ring(q)) continue;
        if (std::floor(p - 0.5) != std::floor(q - 0.5)) {
          a_at_a += difference(a, x, y, dx, dy);
          b_at_a += difference(b, x, y, dx, dy);
          ++r.a_pairs;
        }
        if (std::floor(p + shift - 0.5) != std::floor(q + shift - 0.5)) {
          a_at_b += difference(a, x, y, dx, dy);
          b_at_b += difference(b, x, y, dx, dy);
          ++r.b_pairs;
        }
      }
  r.a_over_b = a_at_a / b_at_a;
  r.b_over_a = b_at_b / a_at_b;
  r.seam = std::sqrt(r.a_over_b * r.b_over_a);
  return r;
}

TEST_F(VectorMapTest, NoSeamWhereTheLensChangesTheLevel) {
  // The Europe map of docs/sources.md framed 1024 x 977 (scale 8: 8 texels a frame pixel at level
  // 0), and the same map framed 1448 px wide, so that its levels are sqrt(2) finer, half a level
  // from the first's. Two zoom-4 lenses over the Low Countries: the geometric focus lens (as
  // docs/sources.md shows it), and a flat-top lens whose magnification falls continuously from 4 to
  // 1 (raised cosine), so that the level changes all across its ring.
  const std::string examples = std::string(GEOLENS_SOURCE_DIR) + "/examples/";
  SourceFileOptions options;
  options.width = 1024;
  options.style = examples + "europe_style.json";
  const SourceFile file = geolens::open_source(examples + "europe.geojson", options);
  options.width = 1448;
  const SourceFile finer = geolens::open_source(examples + "europe.geojson", options);
  const int width = file.frame_width, height = file.frame_height;
  const double finer_scale = finer.scale * finer.frame_width / width;
  const double shift = std::log2(finer_scale / file.scale);
  ASSERT_NEAR(shift, 0.5, 0.01);
  ASSERT_EQ(file.level_band, 0.25);

  const geolens::GeometricLens geometric(width, height);
  geolens::CircleLens flattop;
  flattop.center = {378, 420};
  flattop.radius = 400;  // on screen; its flat top 200
  flattop.zoom = 4;
  const std::pair<std::string, WarpMesh> lenses[] = {
      {"focus lens",
       geometric
           .solve(geolens::parse_lens_spec("circle:378,420,70:4", 2, geolens::Profile::kGaussian, 0,
                                           width, height))
           .warp},
      {"flat-top cosine lens",
       geolens::classic_warp(geolens::ClassicLens::kFlattopCosine, {flattop}, width, height)}};
  for (const auto& [name, warp] : lenses) {
    const std::vector<double> lods =
        pixel_lods(warp, file.scale, file.source->levels(), width, height);
    const double focus_lod = lods[size_t(420) * size_t(width) + 378];
    const double context_lod = lods[size_t(5) * size_t(width) + 5];
    EXPECT_NEAR(focus_lod, 1, 0.1) << name;  // 8 texels a frame pixel magnified 4x: level 1
    EXPECT_EQ(context_lod, 3) << name;
    auto measure = [&](double band) {
      geolens::RenderOptions render_options;
      render_options.width = width;
      render_options.height = height;
      render_options.source_scale = file.scale;
      render_options.level_band = band;
      const Image a = geolens::render(warp, *file.source, render_options);
      render_options.source_scale = finer_scale;
      const Image b = geolens::render(warp, *finer.source, render_options);
      return seam_ratio(a, b, lods, shift, focus_lod, context_lod);
    };
    const SeamRatio blended = measure(file.level_band);
    // Levels switched at the midpoint, not blended: the seam the ratio must see.
    const SeamRatio switched = measure(1e-3);
    std::cout << name << ": blended " << blended.seam << " (" << blended.a_over_b << ", "
              << blended.b_over_a << "; " << blended.a_pairs << " and " << blended.b_pairs
              << " pairs), switched " << switched.seam << " (" << switched.a_over_b << ", "
              << switched.b_over_a << ")\n";
    EXPECT_GT(blended.a_pairs, 5000) << name;
    EXPECT_GT(blended.b_pairs, 5000) << name;
    EXPECT_LE(blended.seam, 1.1) << name;   // measured 0.97, 1.04
    EXPECT_GE(switched.seam, 1.2) << name;  // measured 1.33, 1.32
  }
}

}  // namespace
