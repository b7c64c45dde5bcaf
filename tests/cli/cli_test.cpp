// Runs the real `geolens` binary: exit codes, one-line errors, no partial outputs, the stats
// document, the identity at zoom 1, and the exported flattening checked by an independent ARAP.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "geolens/io/image.h"
#include "support/arap_reference.h"
#include "support/cli_runner.h"
#include "support/scratch_folder.h"

namespace geolens {
namespace {

namespace fs = std::filesystem;

using testing::CliRun;

class Cli : public testing::ScratchFolderTest {
 protected:
  void SetUp() override {
    ScratchFolderTest::SetUp();
    // A 256 x 192 smooth colour pattern with fine stripes.
    Image image(256, 192, 3);
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        uint8_t* p = image.at(x, y);
        p[0] = uint8_t(x);
        p[1] = uint8_t(y + 40);
        p[2] = uint8_t(((x / 4 + y / 4) % 2) * 200 + 20);
      }
    save_image(path("in.png"), image);
  }

  CliRun run(const std::string& arguments) const {
    return testing::run_cli(arguments, path("stderr.txt"));
  }

  // Bad input: exit 2, exactly one line on stderr, no output written.
  void expect_rejected(const std::string& arguments, const std::string& mentions) {
    SCOPED_TRACE(arguments);
    const CliRun r = run(arguments);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(mentions), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(path("out.png")));
    EXPECT_FALSE(fs::exists(path("stats.json")));
    for (const auto& entry : fs::directory_iterator(dir_))
      EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
  }
};

TEST_F(Cli, RejectsEveryBadInputWithOneLineAndExitTwo) {
  const std::string in = path("in.png"),
                    out = " -o " + path("out.png") + " --stats " + path("stats.json");
  expect_rejected("magnify " + path("missing.png") + out + " --lens circle:50,50,20",
                  "missing.png");
  {
    std::ofstream corrupt(path("corrupt.png"), std::ios::binary);
    corrupt << "\x89PNG\r\n\x1a\nthis is not a png at all";
  }
  expect_rejected("magnify " + path("corrupt.png") + out + " --lens circle:50,50,20",
                  "corrupt.png");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,0", "radius");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,-4", "radius");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,nan", "radius");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,20:0", "zoom");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,20:-2", "zoom");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,20:inf", "zoom");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,20:9", "zoom");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,20 --zoom 0.5", "zoom");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,20 --alpha -0.1", "alpha");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,20 --alpha nan", "alpha");
  expect_rejected("magnify " + in + out + " --lens circle:300,50,20", "outside");
  expect_rejected("magnify " + in + out + " --lens circle:50,-1,20", "outside");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,20 --mesh 3", "mesh");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,20 --mesh 1001", "mesh");
  expect_rejected("magnify " + in + " -o " + path("nowhere/out.png") + " --lens circle:50,50,20",
                  "nowhere");
  expect_rejected("magnify " + in + " -o " + in + " --lens circle:50,50,20", "input");
  expect_rejected("magnify " + in + " -o " + path("out.gif") + " --lens circle:50,50,20",
                  "out.gif");
  expect_rejected("magnify " + in + out + " --lens square:50,50,20", "circle:");
  expect_rejected("magnify " + in + out, "--lens");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,20 --profile cone", "cone");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,20 --model ridge", "ridge");
  expect_rejected("magnify " + in + out + " --lens circle:50,50,20 --size 0x10", "--size");
}

TEST_F(Cli, RejectsBadPolygonsAndMasks) {
  const std::string in = path("in.png"),
                    out = " -o " + path("out.png") + " --stats " + path("stats.json");
  auto polygon = [&](const std::string& name, const std::string& text) {
    std::ofstream(path(name)) << text;
    return " --lens polygon:" + path(name);
  };
  expect_rejected("magnify " + in + out + polygon("two.txt", "10 10\n50 10\n"), "3");
  expect_rejected("magnify " + in + out + polygon("flat.txt", "10 10\n50 10\n90 10\n"), "area");
  expect_rejected("magnify " + in + out + polygon("bowtie.txt", "10 10\n90 90\n90 10\n20 60\n"),
                  "intersect");
  expect_rejected("magnify " + in + out + polygon("outside.txt", "10 10\n400 10\n10 90\n"),
                  "outside");
  expect_rejected("magnify " + in + out + polygon("words.txt", "10 10\nten 90\n90 10\n"),
                  "words.txt");
  expect_rejected("magnify " + in + out + " --lens polygon:" + path("none.txt"), "none.txt");
  save_image(path("empty.png"), Image(256, 192, 1, 0));
  expect_rejected("magnify " + in + out + " --lens mask:" + path("empty.png"), "non-zero");
  save_image(path("small.png"), Image(100, 100, 1, 255));
  expect_rejected("magnify " + in + out + " --lens mask:" + path("small.png"), "100x100");
  expect_rejected("magnify " + in + out + " --lens mask:" + path("none.png"), "none.png");
}

// A thresholded photograph's object (the cup rim, thin and wide parts) magnified as a whole.
TEST_F(Cli, MaskOfARealObjectReachesItsZoom) {
  const std::string examples = std::string(GEOLENS_SOURCE_DIR) + "/examples/";
  const CliRun r =
      run("magnify " + examples + "coffee.jpg -o " + path("out.png") + " --lens mask:" + examples +
          "coffee_rim_mask.png:2 --model auto --stats " + path("stats.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(path("stats.json"));
  const nlohmann::json s = nlohmann::json::parse(in);
  ASSERT_EQ(s.at("lenses").size(), 1u);
  const nlohmann::json& lens = s.at("lenses")[0];
  EXPECT_EQ(lens.at("kind"), "mask");
  EXPECT_EQ(s.at("model"), "field");  // auto: a mask is not a circle
  EXPECT_NEAR(lens.at("zoom_measured").get<double>(), 2.0, 0.1);
  EXPECT_EQ(s.at("flipped").get<int>(), 0);
  // The bounding box is the rim's: inside the image, wider than tall.
  const std::vector<double> box = lens.at("bbox");
  EXPECT_GT(box[2] - box[0], box[3] - box[1]);
}

TEST_F(Cli, HelpAndVersionSucceed) {
  EXPECT_EQ(run("--help").code, 0);
  EXPECT_EQ(run("magnify --help").code, 0);
  EXPECT_EQ(run("--version").code, 0);
  EXPECT_EQ(run("").code, 2);
}

TEST_F(Cli, ZoomOneReproducesTheInput) {
  ASSERT_EQ(
      run("magnify " + path("in.png") + " -o " + path("out.png") + " --lens circle:128,96,60:1")
          .code,
      0);
  const Image in = load_image(path("in.png")), out = load_image(path("out.png"));
  ASSERT_EQ(out.width, in.width);
  ASSERT_EQ(out.height, in.height);
  double difference = 0;
  for (size_t i = 0; i < in.pixels.size(); ++i)
    difference += std::abs(int(in.pixels[i]) - int(out.pixels[i]));
  EXPECT_LT(difference / double(in.pixels.size()), 1.0);
}

TEST_F(Cli, StatsHoldEveryField) {
  const CliRun r = run("magnify " + path("in.png") + " -o " + path("out.jpg") +
                       " --lens circle:128,96,50:2 --lens circle:40,40,20:1.5 --size 128x96" +
                       " --model auto --stats " + path("stats.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(load_image(path("out.jpg")).width, 128);
  std::ifstream in(path("stats.json"));
  const nlohmann::json s = nlohmann::json::parse(in);
  EXPECT_GT(s.at("vertices").get<int>(), 0);
  EXPECT_GT(s.at("triangles").get<int>(), 0);
  EXPECT_EQ(s.at("energy").size(), s.at("iterations").get<size_t>() + 1);
  EXPECT_EQ(s.at("flipped").get<int>(), 0);
  EXPECT_EQ(s.at("model"), "lift");  // auto: circles only
  EXPECT_EQ(s.at("options").at("model"), "auto");
  ASSERT_EQ(s.at("lenses").size(), 2u);
  for (const auto& lens : s.at("lenses")) {
    EXPECT_EQ(lens.at("center").size(), 2u);
    EXPECT_GT(lens.at("radius").get<double>(), 0);
    EXPECT_NEAR(lens.at("zoom_measured").get<double>() / lens.at("zoom_requested").get<double>(),
                1.0, 0.1);
  }
  EXPECT_GE(s.at("distortion").at("conformal_max").get<double>(),
            s.at("distortion").at("conformal_mean").get<double>());
  for (const char* stage : {"lift", "texture", "factorize", "iterate", "render", "total"})
    EXPECT_GE(s.at("timings_ms").at(stage).get<double>(), 0) << stage;
}

// With plain cotan weights, the rigid metric and a free boundary, the flattening minimizes the
// ARAP energy: an independent gradient descent started from it finds nothing lower.
TEST_F(Cli, FreeCotanFlatteningIsAConvergedArapMinimum) {
  const CliRun r =
      run("magnify " + path("in.png") + " -o " + path("out.png") +
          " --lens circle:128,96,60:2 --model lift --mesh 40 --weights cotan --metric paper" +
          " --alpha 0 --boundary free --tolerance 1e-12 --max-iterations 5000" + " --export-mesh " +
          path("mesh"));
  ASSERT_EQ(r.code, 0) << r.err;
  Eigen::MatrixX3d V3, flat;
  Eigen::MatrixX3i F, F2;
  testing::read_obj(path("mesh_3d.obj"), V3, F);
  testing::read_obj(path("mesh_flat.obj"), flat, F2);
  ASSERT_EQ(F, F2);
  ASSERT_EQ(V3.rows(), flat.rows());
  EXPECT_EQ(flat.col(2).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(V3.col(2).maxCoeff(), 1.0);  // the mesh really was lifted
  const Eigen::MatrixX2d X = flat.leftCols<2>();
  const double ours = testing::arap_energy(V3, F, X);
  const Eigen::MatrixX2d descended = testing::arap_descend(V3, F, X, 200);
  const double theirs = testing::arap_energy(V3, F, descended);
  EXPECT_GT(ours, 0);
  EXPECT_GE(theirs, ours * (1 - 1e-6)) << "ours " << ours << " independent " << theirs;
  // The independent descent does lower an unconverged flattening (the check has teeth).
  const Eigen::MatrixX2d start = V3.leftCols<2>();
  EXPECT_LT(testing::arap_energy(V3, F, testing::arap_descend(V3, F, start, 200)),
            testing::arap_energy(V3, F, start) * 0.99);
}

}  // namespace
}  // namespace geolens
