// `geolens map` and `magnify --overlay` through the real binary: CSV and GeoJSON mapped forward and
// back to where they were, standard input and output, one-line refusals with exit 2 and nothing
// written, and an overlay drawn on the output.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "geolens/io/geojson.h"
#include "geolens/io/image.h"
#include "geolens/io/point_csv.h"
#include "geolens/render/overlay.h"
#include "support/cli_test.h"

namespace geolens {
namespace {

namespace fs = std::filesystem;

using testing::CliRun;

const std::string kLens = " --lens circle:256,192,60:2";

class MapCli : public testing::CliTest {
 protected:
  void SetUp() override {
    ScratchFolderTest::SetUp();
    save_image(path("in.png"), Image(512, 384, 3, 200));
    write("in.csv", "x,y,name\n256,192,centre\n270.25,200.5,near\n10,10,far\n500,380,corner\n");
    write("in.geojson", R"({"type":"FeatureCollection","features":[)"
                        R"({"type":"Feature","id":1,"geometry":{"type":"LineString","coordinates":)"
                        R"([[40,220],[472,220]]},"properties":{"name":"road","lanes":2}},)"
                        R"({"type":"Feature","geometry":{"type":"Point","coordinates":[270,180]},)"
                        R"("properties":{"name":"stop"}},)"
                        R"({"type":"Feature","geometry":{"type":"Polygon","coordinates":)"
                        R"([[[220,160],[300,160],[300,230],[220,160]]]},"properties":null}]})");
  }

  void write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
  }
  std::string read(const std::string& name) const {
    std::ifstream in(path(name), std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  // The standard output of `geolens arguments`, and its exit code.
  std::pair<std::string, int> output_of(const std::string& arguments) const {
    const std::string command =
        std::string(GEOLENS_CLI) + " " + arguments + " 2> " + path("stderr.txt");
    std::FILE* pipe = popen(command.c_str(), "r");
    std::string out;
    char buffer[4096];
    for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
    const int status = pclose(pipe);
    return {out, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
  }
};

TEST_F(MapCli, CsvGoesThroughTheLensAndBack) {
  const CliRun there = run("map " + path("in.csv") + " --image " + path("in.png") + kLens + " -o " +
                           path("screen.csv"));
  ASSERT_EQ(there.code, 0) << there.err;
  EXPECT_EQ(there.err.find("dropped"), std::string::npos) << there.err;
  const PointTable in = read_point_csv(path("in.csv")), screen = read_point_csv(path("screen.csv"));
  ASSERT_EQ(screen.points.rows(), in.points.rows());
  EXPECT_EQ(screen.header, "x,y,name");
  EXPECT_EQ(screen.rest, in.rest);
  EXPECT_LT((screen.points.row(0) - in.points.row(0)).norm(), 1e-9);  // the centre stays
  // Magnified about the centre: twice as far from it.
  EXPECT_NEAR((screen.points.row(1) - in.points.row(0)).norm(),
              2 * (in.points.row(1) - in.points.row(0)).norm(), 0.05);
  const CliRun back = run("map " + path("screen.csv") + " --size 512x384 --inverse" + kLens +
                          " -o " + path("back.csv"));
  ASSERT_EQ(back.code, 0) << back.err;
  const PointTable returned = read_point_csv(path("back.csv"));
  ASSERT_EQ(returned.points.rows(), in.points.rows());
  EXPECT_LT((returned.points - in.points).rowwise().norm().maxCoeff(), 1e-6);
}

TEST_F(MapCli, StandardInputAndOutput) {
  const auto [file_out, code] = output_of("map " + path("in.geojson") + " --size 512x384" + kLens);
  ASSERT_EQ(code, 0) << read("stderr.txt");
  const auto [stdin_out, stdin_code] =
      output_of("map - --format geojson --size 512x384" + kLens + " < " + path("in.geojson"));
  ASSERT_EQ(stdin_code, 0) << read("stderr.txt");
  EXPECT_EQ(stdin_out, file_out);
  ASSERT_EQ(
      run("map " + path("in.geojson") + " --size 512x384" + kLens + " -o " + path("out.geojson"))
          .code,
      0);
  EXPECT_EQ(read("out.geojson"), file_out);
  // The output is GeoJSON with the input's ids and properties, the line bent by the lens.
  const VectorData mapped = parse_geojson(file_out, "stdout");
  ASSERT_EQ(mapped.features.size(), 3u);
  EXPECT_EQ(mapped.features[0].id, "1");
  EXPECT_EQ(mapped.features[0].properties, R"({"name":"road","lanes":2})");
  const Eigen::MatrixX2d& road = mapped.features[0].geometry->paths[0];
  EXPECT_GT(road.rows(), 100);                 // densified at 2 px
  EXPECT_GT(road.col(1).maxCoeff() - 220, 5);  // pushed away from the centre by the lens
  // A coarser --max-segment: ceil(432 / 50) segments; CSV from standard input with --format.
  const auto [coarse, coarse_code] =
      output_of("map " + path("in.geojson") + " --size 512x384 --max-segment 50" + kLens);
  ASSERT_EQ(coarse_code, 0);
  EXPECT_EQ(parse_geojson(coarse, "coarse").features[0].geometry->paths[0].rows(), 10);  // 432 / 50
  const auto [csv, csv_code] =
      output_of("map - --format csv --size 512x384" + kLens + " < " + path("in.csv"));
  ASSERT_EQ(csv_code, 0);
  EXPECT_EQ(parse_point_csv(csv, "csv").points.rows(), 4);
}

TEST_F(MapCli, PointsOutsideAreDroppedWithAWarning) {
  write("outside.csv", "1,1\n-5,3\n600,20\n");
  const CliRun r =
      run("map " + path("outside.csv") + " --size 512x384" + kLens + " -o " + path("out.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("2 points dropped"), std::string::npos) << r.err;
  EXPECT_EQ(read_point_csv(path("out.csv")).points.rows(), 1);
}

TEST_F(MapCli, RefusesBadInputWithOneLineAndExitTwo) {
  const std::string size = " --size 512x384" + kLens, out = " -o " + path("out.geojson");
  write("bad.csv", "x,y\n1,2\n3,oops\n");
  expect_refused("map " + path("bad.csv") + size + " -o " + path("out.csv"),
                 path("bad.csv") + ":3: expected two finite numbers");
  write("bad.geojson", R"({"type":"FeatureCollection","features":[)"
                       R"({"type":"Feature","geometry":null,"properties":null},)"
                       R"({"type":"Feature","geometry":{"type":"LineString","coordinates":)"
                       R"([[1,2]]},"properties":null}]})");
  expect_refused("map " + path("bad.geojson") + size + out,
                 "'" + path("bad.geojson") + "': feature 1: LineString");
  write("broken.geojson", "{\"type\":");
  expect_refused("map " + path("broken.geojson") + size + out, "not JSON");
  write("in.txt", "1,2\n");
  expect_refused("map " + path("in.txt") + size, "--format");
  expect_refused("map - " + size + " < " + path("in.csv"), "--format");
  expect_refused("map " + path("in.csv") + size + " --format svg", "svg");
  expect_refused("map " + path("in.csv") + size + out, "the output has the input's format");
  expect_refused("map " + path("in.csv") + kLens, "--image FILE or --size WxH");
  expect_refused("map " + path("in.csv") + size + " --max-segment 0", "--max-segment");
  expect_refused("map " + path("in.csv") + size + " --max-segment 5e-5",
                 "--max-segment: must be at least 0.01 pixels");
  expect_refused("map " + path("missing.csv") + size, "missing.csv");
  // The points a CSV may hold: a limit that names itself and its option, raised by it.
  write("three.csv", "x,y\n1,2\n3,4\n5,6\n");
  expect_refused("map " + path("three.csv") + size + " --max-points 2 -o " + path("out.csv"),
                 "more than the 2 points read (max_points; --max-points raises it");
  expect_refused("map - " + size + " --format csv --max-points 2 < " + path("three.csv"),
                 "more than the 2 points read");
  EXPECT_EQ(run("map " + path("three.csv") + size + " --max-points 3 -o " + path("out.csv")).code,
            0);
  for (const char* bad : {"0", "-1", "1.5", "2e9", "nan"})
    expect_refused("map " + path("in.csv") + size + " --max-points " + bad,
                   "--max-points: must be");
  // The same limit on a GeoJSON input's positions (a CSV's points are a GeoJSON's positions).
  expect_refused("map " + path("in.geojson") + size + " --max-points 1 -o " + path("out.geojson"),
                 "positions read in all (max_points; --max-points raises it)");
  expect_refused("map " + path("in.csv") + " --image " + path("missing.png") + kLens,
                 "missing.png");
  expect_refused("map " + path("in.csv") + " --size 512x384 --lens circle:700,96,30", "outside");
  expect_refused("map " + path("in.csv") + size + " -o " + path("in.csv"),
                 "would overwrite the input");
  expect_refused("map " + path("in.csv") + size + " -o " + path("./in.csv"),
                 "would overwrite the input");
  expect_refused("map " + path("in.csv") + size + " -o " + path("nowhere/out.csv"), "nowhere");
}

// On a vector map (--image a GeoJSON in degrees) the source side is in degrees: points in
// longitude and latitude go through the lens to screen pixels and --inverse tells them back in
// degrees; with a lens far away (zoom 1) they land where the map draws them; --style frames it
// as magnify does; pixels given as degrees and --style without --image are refused.
TEST_F(MapCli, OnAVectorMapTheSourceSideIsInDegrees) {
  const std::string europe = std::string(GEOLENS_SOURCE_DIR) + "/examples/europe.geojson";
  const std::string style = std::string(GEOLENS_SOURCE_DIR) + "/examples/europe_style.json";
  const std::string image = " --image " + europe + " --style " + style + " --size 800x600";
  write("cities.csv", "lon,lat,name\n2.35,48.86,paris\n13.4,52.52,berlin\n-3.7,40.42,madrid\n");
  const CliRun there = run("map " + path("cities.csv") + image + " --lens circle:300,300,50:2 -o " +
                           path("screen.csv"));
  ASSERT_EQ(there.code, 0) << there.err;
  const CliRun back = run("map " + path("screen.csv") + image +
                          " --lens circle:300,300,50:2 --inverse -o " + path("back.csv"));
  ASSERT_EQ(back.code, 0) << back.err;
  const PointTable in = read_point_csv(path("cities.csv")),
                   screen = read_point_csv(path("screen.csv")),
                   returned = read_point_csv(path("back.csv"));
  ASSERT_EQ(returned.points.rows(), 3);
  EXPECT_LT((returned.points - in.points).rowwise().norm().maxCoeff(), 1e-6);
  EXPECT_GT((screen.points - in.points).rowwise().norm().minCoeff(), 50);  // pixels, not degrees
  // At zoom 1 the screen is the frame: Paris where magnify --overlay draws its dot, on the map.
  const CliRun frame = run("map " + path("cities.csv") + image + " --lens circle:700,100,10:1 -o " +
                           path("frame.csv"));
  ASSERT_EQ(frame.code, 0) << frame.err;
  write("paris.geojson", R"({"type":"Point","coordinates":[2.35,48.86]})");
  ASSERT_EQ(run("magnify " + europe + " --style " + style + " --size 800x600" +
                " --lens circle:700,100,10:1 -o " + path("dot.png") + " --overlay " +
                path("paris.geojson"))
                .code,
            0);
  const Eigen::Vector2d paris = read_point_csv(path("frame.csv")).points.row(0).transpose();
  const Image dot = load_image(path("dot.png"));
  const uint8_t* p = dot.at(int(paris.x()), int(paris.y()));
  const OverlayStyle overlay;
  EXPECT_TRUE(std::equal(overlay.point_colour.begin(), overlay.point_colour.end(), p))
      << int(p[0]) << " " << int(p[1]) << " " << int(p[2]) << " at " << paris.transpose();
  // Pixels are no degrees; a style needs the map.
  write("pixels.csv", "x,y\n400,300\n");
  expect_refused("map " + path("pixels.csv") + image + " --lens circle:300,300,50:2",
                 "point 1: the position (400, 300) is not a longitude");
  expect_refused("map " + path("cities.csv") + " --size 800x600 --style " + style +
                     " --lens circle:300,300,50:2",
                 "--style: is the style of an --image vector map");
  // --max-points bounds the --image vector map's positions too, and magnify's.
  expect_refused(
      "map " + path("cities.csv") + image + " --lens circle:300,300,50:2 --max-points 10",
      "(max_points; --max-points raises it)");
  expect_refused("magnify " + europe + " --style " + style + " --size 800x600" +
                     " --lens circle:700,100,10 -o " + path("map.png") + " --max-points 10",
                 "europe.geojson': feature 0");
}

TEST_F(MapCli, MagnifyDrawsTheOverlay) {
  const std::string magnify = "magnify " + path("in.png") + kLens;
  ASSERT_EQ(run(magnify + " -o " + path("plain.png")).code, 0);
  const CliRun r = run(magnify + " -o " + path("drawn.png") + " --overlay " + path("in.geojson") +
                       " --before-after " + path("both.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  const Image plain = load_image(path("plain.png")), drawn = load_image(path("drawn.png"));
  ASSERT_EQ(drawn.width, plain.width);
  const OverlayStyle style;
  int line = 0, point = 0;
  for (int y = 0; y < drawn.height; ++y)
    for (int x = 0; x < drawn.width; ++x) {
      const uint8_t* p = drawn.at(x, y);
      line += std::equal(style.line_colour.begin(), style.line_colour.end(), p);
      point += std::equal(style.point_colour.begin(), style.point_colour.end(), p);
    }
  EXPECT_GT(line, 200);  // the road across the image and the triangle
  EXPECT_GT(point, 10);
  EXPECT_TRUE(fs::exists(path("both.png")));
  // A bad overlay: nothing written.
  write("bad.geojson", R"({"type":"Point","coordinates":[1]})");
  expect_refused(magnify + " -o " + path("out.png") + " --overlay " + path("bad.geojson"),
                 "bad.geojson");
  expect_refused(magnify + " -o " + path("out.png") + " --overlay " + path("missing.geojson"),
                 "missing.geojson");
  // An overlay's positions are bounded by --max-points, named.
  expect_refused(
      magnify + " -o " + path("out.png") + " --overlay " + path("in.geojson") + " --max-points 1",
      "in.geojson': feature 0 LineString coordinates[1]: more than the 1 positions "
      "read in all (max_points; --max-points raises it)");
}

}  // namespace
}  // namespace geolens
