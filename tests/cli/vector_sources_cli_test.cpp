// `geolens magnify` on an SVG and on a vector map (GeoJSON + style) through the real binary: the
// frame from --size, the source's numbers in --stats, labels drawn, and one-line refusals with
// exit 2 and nothing written for a malformed SVG, GeoJSON or style file.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "geolens/io/image.h"
#include "support/cli_test.h"

namespace geolens {
namespace {

using testing::CliRun;

class VectorSourcesCli : public testing::CliTest {
 protected:
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
  }
  nlohmann::json stats() const {
    std::ifstream in(path("stats.json"));
    return nlohmann::json::parse(in);
  }
};

const std::string kExamples = std::string(GEOLENS_SOURCE_DIR) + "/examples/";

TEST_F(VectorSourcesCli, MagnifiesAnSvgFramedBySize) {
  write("a.svg", R"(<svg xmlns="http://www.w3.org/2000/svg" width="432pt" height="360pt">
    <rect x="0" y="0" width="288" height="240" fill="black"/></svg>)");
  const CliRun r = run("magnify " + path("a.svg") + " --size 400x300 --lens circle:300,225,30:2" +
                       " -o " + path("out.png") + " --stats " + path("stats.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const Image out = load_image(path("out.png"));
  EXPECT_EQ(out.width, 400);
  EXPECT_EQ(out.height, 300);
  // The rectangle is the SVG's top-left half: (0, 0) - (200, 150) of the frame.
  EXPECT_LT(out.at(20, 20)[0], 30);
  EXPECT_GT(out.at(380, 20)[0], 225);
  const nlohmann::json source = stats().at("source");
  EXPECT_EQ(source.at("kind"), "svg");
  EXPECT_EQ(source.at("scale"), 8.0);
  EXPECT_GE(source.at("tiles").get<double>(), 1);
}

TEST_F(VectorSourcesCli, MagnifiesTheExampleMapWithItsLabels) {
  const CliRun r = run("magnify " + kExamples + "europe.geojson --style " + kExamples +
                       "europe_style.json --size 512x489 --lens circle:189,210,35:3 -o " +
                       path("out.png") + " --stats " + path("stats.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(load_image(path("out.png")).width, 512);
  const nlohmann::json source = stats().at("source");
  EXPECT_EQ(source.at("kind"), "vector map");
  EXPECT_GT(source.at("labels").get<double>(), 10);
  EXPECT_GT(source.at("features").get<double>(), 500);
}

TEST_F(VectorSourcesCli, RefusesMalformedFilesInOneLine) {
  const std::string lens = " --lens circle:50,50,10:2 -o " + path("out.png");
  write("bad.svg",
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100\" height=\"100\">\n"
        "<rect x=\"1\" <oops/></svg>");
  expect_refused("magnify " + path("bad.svg") + lens, path("bad.svg"));
  write("bad.geojson", R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": null, "geometry": {"type": "Point", "coordinates": [1]}}]})");
  expect_refused("magnify " + path("bad.geojson") + " --size 100x100" + lens, "feature 0");
  write("style.json", R"({"layers": [{"colour": "#ff0000"}]})");
  expect_refused("magnify " + kExamples + "europe.geojson --style " + path("style.json") +
                     " --size 100x100" + lens,
                 "layers[0].colour: unknown key");
  write("style.json", R"({"background": "#ggg"})");
  expect_refused("magnify " + kExamples + "europe.geojson --style " + path("style.json") +
                     " --size 100x100" + lens,
                 "background: '#ggg' is not a colour");
}

}  // namespace
}  // namespace geolens
