// Runs the real `geolens compare`: every output written with the report's full schema, the
// classic lenses matched to the geometric lens's zoom, the identity at zoom 1, and bad input
// rejected with one line, exit code 2 and nothing written.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "geolens/io/image.h"
#include "support/cli_runner.h"
#include "support/scratch_folder.h"

namespace geolens {
namespace {

namespace fs = std::filesystem;

const char* kMethods[] = {"geometric", "zoom_in",        "fisheye",        "fisheye_smooth",
                          "bifocal",   "flattop_linear", "flattop_cosine", "power_ring"};

using testing::CliRun;

class CompareCli : public testing::ScratchFolderTest {
 protected:
  // A size x size colour pattern with fine stripes.
  void write_input(const std::string& name, int size) const {
    Image image(size, size, 3);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        uint8_t* p = image.at(x, y);
        p[0] = uint8_t(x);
        p[1] = uint8_t(y + 40);
        p[2] = uint8_t(((x / 4 + y / 4) % 2) * 200 + 20);
      }
    save_image(path(name), image);
  }

  CliRun run(const std::string& arguments) const {
    return testing::run_cli(arguments, path("stderr.txt"));
  }

  nlohmann::json report(const std::string& out) const {
    std::ifstream in(fs::path(out) / "report.json");
    return nlohmann::json::parse(in);
  }

  // Bad input: exit 2, exactly one line on stderr, and the folder `out` not created (or, if it
  // existed, still empty); no temporary file left anywhere.
  void expect_rejected(const std::string& arguments, const std::string& mentions,
                       const std::string& out) {
    SCOPED_TRACE(arguments);
    const bool existed = fs::is_directory(out);
    const CliRun r = run(arguments);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(mentions), std::string::npos) << r.err;
    if (existed)
      EXPECT_TRUE(fs::is_empty(out));
    else
      EXPECT_FALSE(fs::exists(out));
    for (const auto& entry : fs::recursive_directory_iterator(dir_))
      EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
  }
};

// The setting: 1024 x 1024, r = 150, zoom 2, the paper's lift (the classic lenses
// then have the region's radius).
TEST_F(CompareCli, WritesEveryOutputAndMatchesTheZoom) {
  write_input("in.png", 1024);
  const std::string out = path("out");
  const CliRun r =
      run("compare " + path("in.png") + " --lens circle:512,512,150:2 --model lift -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* name : kMethods) {
    for (const std::string suffix : {".png", "_heatmap.png"}) {
      const Image image = load_image((fs::path(out) / (name + suffix)).string());
      EXPECT_EQ(image.width, 1024) << name << suffix;
      EXPECT_GE(image.height, 1024) << name << suffix;  // the heatmap adds its scale below
    }
  }
  EXPECT_GT(load_image((fs::path(out) / "panel.png").string()).width, 4 * 256);
  std::ifstream md(fs::path(out) / "report.md");
  std::stringstream text;
  text << md.rdbuf();
  for (const char* name : kMethods)
    EXPECT_NE(text.str().find(std::string("| ") + name + " |"), std::string::npos);

  const nlohmann::json j = report(out);
  ASSERT_EQ(j.size(), 1u);
  const nlohmann::json& methods = j.at("methods");
  ASSERT_EQ(methods.size(), std::size(kMethods));
  const double geometric_zoom = methods[0].at("zoom_center").get<double>();
  EXPECT_NEAR(geometric_zoom, 2, 0.1);
  for (size_t i = 0; i < std::size(kMethods); ++i) {
    const nlohmann::json& m = methods[i];
    SCOPED_TRACE(kMethods[i]);
    EXPECT_EQ(m.at("name").get<std::string>(), kMethods[i]);
    EXPECT_EQ(m.size(), 7u);
    ASSERT_EQ(m.at("lenses").size(), 1u);
    EXPECT_GE(m.at("lenses")[0].at("focus").at("uniformity").get<double>(), 1);
    EXPECT_NEAR(m.at("zoom_center").get<double>() / geometric_zoom, 1, 0.05);
    // One definition of focus uniformity: over the region given, as per lens and in --stats.
    EXPECT_EQ(m.at("focus_uniformity").get<double>(),
              m.at("lenses")[0].at("focus").at("uniformity").get<double>());
    const nlohmann::json& d = m.at("distortion");
    EXPECT_EQ(d.size(), 4u);
    for (const char* zone : {"focus", "transition", "context", "overall"}) {
      EXPECT_EQ(d.at(zone).size(), 2u) << zone;
      const double mean = d.at(zone).at("mean").get<double>(),
                   max = d.at(zone).at("max").get<double>();
      EXPECT_GE(mean, 0) << zone;
      EXPECT_GE(max, mean) << zone;
    }
    EXPECT_GE(m.at("occluded_percent").get<double>(), 0);
    EXPECT_EQ(m.at("flipped").get<int>(), 0);
  }
  // What the measures must show: the zoom-in hides its ring (pi (150^2 - 75^2) of 1024^2, about
  // 5.1 %) and distorts nothing; Sarkar-Brown's rim distortion is about d = zoom - 1; flat tops
  // keep their focus zone (a r / zoom) undistorted, but with the lift model the region given
  // reaches past their flat top, so over it they are far from uniform.
  EXPECT_NEAR(methods[1].at("occluded_percent").get<double>(), 5.1, 0.15);
  EXPECT_LT(methods[1].at("distortion").at("overall").at("max").get<double>(), 1e-9);
  EXPECT_NEAR(methods[2].at("distortion").at("transition").at("max").get<double>(),
              geometric_zoom - 1, 0.25);
  for (size_t i : {4, 5, 6}) {
    EXPECT_GT(methods[i].at("focus_uniformity").get<double>(), 1.5);
    EXPECT_LT(methods[i].at("distortion").at("focus").at("max").get<double>(), 1e-9);
  }
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
}

// --sweep: one lens over footprints zoom + 1 to 4 zoom, every method at each, as JSON, Markdown
// and a plot; two lenses are refused.
TEST_F(CompareCli, SweepWritesTheTradeOff) {
  write_input("in.png", 512);
  const std::string out = path("out");
  const CliRun r =
      run("compare " + path("in.png") + " --lens circle:256,256,25:2 --sweep -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(fs::path(out) / "sweep.json");
  const nlohmann::json points = nlohmann::json::parse(in).at("points");
  EXPECT_EQ(points.size(), 4 * std::size(kMethods));  // F = 3, 4, 6, 8
  for (const auto& p : points) {
    EXPECT_GT(p.at("ratio").get<double>(), 2);
    EXPECT_GE(p.at("shape_max").get<double>(), 0);
  }
  EXPECT_GT(load_image((fs::path(out) / "sweep.png").string()).width, 0);
  EXPECT_TRUE(fs::exists(fs::path(out) / "sweep.md"));
  EXPECT_EQ(run("compare " + path("in.png") +
                " --lens circle:100,100,20 --lens circle:400,400,20 --sweep -o " + path("two"))
                .code,
            2);
}

// A polygon and a mask lens: the classic lenses, radial, are fitted to the region's disk (about
// its peak, radius its reach), which their flat top shows at full zoom, so over the region given
// they are uniform; the geometric lens too, within a smaller footprint; the report says so.
TEST_F(CompareCli, PolygonAndMaskLensesAgainstClassicLensesFittedToTheirDisk) {
  write_input("in.png", 512);
  std::ofstream(path("square.txt")) << "200 200\n300 200\n300 280\n200 280\n";
  Image mask(512, 512, 1, 0);
  for (int y = 230; y < 290; ++y)
    for (int x = 220; x < 300; ++x) mask.at(x, y)[0] = 255;
  save_image(path("mask.png"), mask);
  for (const std::string lens : {"polygon:" + path("square.txt"), "mask:" + path("mask.png")}) {
    SCOPED_TRACE(lens);
    const std::string out = path("out_" + lens.substr(0, lens.find(':')));
    const CliRun r = run("compare " + path("in.png") + " --lens " + lens + ":2 -o " + out);
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json methods = report(out).at("methods");
    ASSERT_EQ(methods.size(), std::size(kMethods));
    for (size_t i = 0; i < std::size(kMethods); ++i) {
      SCOPED_TRACE(kMethods[i]);
      EXPECT_EQ(methods[i].at("name"), kMethods[i]);
      EXPECT_TRUE(fs::exists(fs::path(out) / (std::string(kMethods[i]) + ".png")));
      const nlohmann::json& focus = methods[i].at("lenses")[0].at("focus");
      EXPECT_EQ(methods[i].at("focus_uniformity").get<double>(),
                focus.at("uniformity").get<double>());
      EXPECT_NEAR(methods[i].at("zoom_center").get<double>(), 2, 0.1);
    }
    for (size_t i : {0, 4, 5, 6, 7}) {  // the geometric lens and the flat tops
      EXPECT_LT(methods[i].at("focus_uniformity").get<double>(), 1.02) << kMethods[i];
      EXPECT_NEAR(methods[i].at("lenses")[0].at("focus").at("zoom").get<double>(), 2, 0.05)
          << kMethods[i];
    }
    // The geometric lens's footprint follows the region, the classic ones fill its disk: it
    // disturbs less of the image, and less on average (its largest distortion, at the corners, is
    // not lower: docs/design.md, "compare with polygons and masks").
    auto mean = [](const nlohmann::json& m) {
      return m.at("distortion").at("overall").at("mean").get<double>();
    };
    auto footprint = [](const nlohmann::json& m) {
      return m.at("lenses")[0].at("footprint_radius").get<double>();
    };
    for (size_t i : {4, 5, 6, 7}) {
      EXPECT_LT(mean(methods[0]), mean(methods[i])) << kMethods[i];
      EXPECT_LT(footprint(methods[0]), 0.9 * footprint(methods[i])) << kMethods[i];
    }
    std::ifstream md(fs::path(out) / "report.md");
    std::stringstream text;
    text << md.rdbuf();
    EXPECT_NE(text.str().find("the classic lenses magnify the disk about the region's peak"),
              std::string::npos)
        << text.str();
  }
}

// With the focus model (the default) the classic lenses get the focus lens's footprint as their
// radius, so each shows the same region at full zoom: the geometric lens's focus is uniform and
// undistorted, nothing beyond its footprint moves, and its largest shape distortion is below
// every classic lens with a uniform focus but the bound-reaching power ring.
TEST_F(CompareCli, FocusLensAgainstClassicLensesOfTheSameFootprint) {
  write_input("in.png", 1024);
  const std::string out = path("out");
  const CliRun r =
      run("compare " + path("in.png") + " --lens circle:512,512,100:2 --mesh 200 -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json methods = report(out).at("methods");
  ASSERT_EQ(methods.size(), std::size(kMethods));
  const nlohmann::json& geometric = methods[0].at("lenses")[0];
  EXPECT_NEAR(geometric.at("focus").at("zoom").get<double>(), 2, 0.02);
  EXPECT_LT(geometric.at("focus").at("uniformity").get<double>(), 1.01);
  EXPECT_LT(geometric.at("focus").at("shape_max").get<double>(), 0.01);
  EXPECT_EQ(geometric.at("displacement_beyond_footprint").get<double>(), 0);
  auto worst = [](const nlohmann::json& m) {
    return m.at("distortion").at("overall").at("max").get<double>();
  };
  for (size_t i : {4, 5, 6}) {  // bifocal, flat-top linear, flat-top cosine
    SCOPED_TRACE(kMethods[i]);
    EXPECT_NEAR(methods[i].at("lenses")[0].at("focus").at("uniformity").get<double>(), 1, 1e-9);
    EXPECT_LT(worst(methods[0]), worst(methods[i]));
  }
  EXPECT_GT(worst(methods[0]), worst(methods[7]));  // no lens beats the bound
}

TEST_F(CompareCli, ZoomOneIsTheIdentityForEveryMethod) {
  write_input("in.png", 200);
  const std::string out = path("out");
  const CliRun r = run("compare " + path("in.png") + " --lens circle:100,100,60:1 -o " + out +
                       " --format jpg --tile 64 --baseline-mesh 60");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(fs::path(out) / "panel.jpg"));
  const nlohmann::json methods = report(out).at("methods");
  for (const nlohmann::json& m : methods) {
    SCOPED_TRACE(m.at("name").get<std::string>());
    EXPECT_NEAR(m.at("zoom_center").get<double>(), 1, 1e-9);
    EXPECT_NEAR(m.at("focus_uniformity").get<double>(), 1, 1e-9);
    EXPECT_LT(m.at("distortion").at("overall").at("max").get<double>(), 1e-9);
    EXPECT_NEAR(m.at("occluded_percent").get<double>(), 0, 1e-9);
  }
}

// With --extent local the geometric lens solves a patch and frames it with an identity mesh; the
// Eq. 7 energy is taken over the patch.
TEST_F(CompareCli, LocalExtentIsMeasuredLikeTheRest) {
  write_input("in.png", 256);
  const std::string out = path("out");
  const CliRun r = run("compare " + path("in.png") + " --lens circle:128,128,50:2 -o " + out +
                       " --extent local --baseline-mesh 60 --tile 64");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json methods = report(out).at("methods");
  ASSERT_EQ(methods.size(), std::size(kMethods));
  for (const nlohmann::json& m : methods) {
    EXPECT_NEAR(m.at("zoom_center").get<double>() / methods[0].at("zoom_center").get<double>(), 1,
                0.05);
    EXPECT_EQ(m.at("flipped").get<int>(), 0);
  }
  std::ifstream md(fs::path(out) / "report.md");
  std::stringstream text;
  text << md.rdbuf();
  EXPECT_NE(text.str().find("Eq. 7 energy"), std::string::npos);
}

TEST_F(CompareCli, RejectsEveryBadInputWithOneLineAndExitTwo) {
  write_input("in.png", 200);
  const std::string in = path("in.png"), out = path("out"), lens = " --lens circle:100,100,50:2";
  expect_rejected("compare " + path("missing.png") + " -o " + out + lens, "missing.png", out);
  {
    std::ofstream corrupt(path("corrupt.png"), std::ios::binary);
    corrupt << "\x89PNG\r\n\x1a\nthis is not a png at all";
  }
  expect_rejected("compare " + path("corrupt.png") + " -o " + out + lens, "corrupt.png", out);
  {
    std::ofstream file(path("a_file"));
    file << "x";
  }
  expect_rejected("compare " + in + " -o " + path("a_file") + lens, "not a folder", out);
  expect_rejected("compare " + in + " -o " + path("nowhere/out") + lens, "nowhere",
                  path("nowhere"));
  expect_rejected("compare " + in + " -o " + out, "--lens", out);
  expect_rejected("compare " + in + " -o " + out + " --lens circle:100,100,0", "radius", out);
  expect_rejected("compare " + in + " -o " + out + " --lens circle:100,100,50:9", "zoom", out);
  expect_rejected("compare " + in + " -o " + out + " --lens circle:300,100,50", "outside", out);
  expect_rejected("compare " + in + " -o " + out + " --lens square:100,100,50", "circle:", out);
  expect_rejected(
      "compare " + in + " -o " + out + " --lens circle:60,60,40 --lens circle:100,100,40",
      "overlap", out);
  expect_rejected("compare " + in + " -o " + out + lens + " --format gif", "--format", out);
  expect_rejected("compare " + in + " -o " + out + lens + " --tile 10", "--tile", out);
  expect_rejected("compare " + in + " -o " + out + lens + " --baseline-mesh 3", "--baseline-mesh",
                  out);
  expect_rejected("compare " + in + " -o " + out + lens + " --heat-max -1", "--heat-max", out);
  expect_rejected("compare " + in + " -o " + out + lens + " --mesh 2", "mesh", out);
  expect_rejected("compare " + in + " -o " + out + lens + " --profile cone", "cone", out);
  expect_rejected("compare " + in + " -o " + out + lens + " --unknown", "unknown", out);
  // An existing output folder that holds the input under an output's name.
  fs::create_directories(out);
  write_input("out/geometric.png", 200);
  expect_rejected("compare " + path("out/geometric.png") + " -o " + out + lens, "input",
                  out + "/x");
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 1);
  // An existing empty folder stays empty on bad input.
  fs::create_directories(path("empty"));
  expect_rejected("compare " + in + " -o " + path("empty") + lens + " --alpha 2", "alpha",
                  path("empty"));
}

// An output file that is an existing folder, or that is an input (here a polygon file in the
// output folder under an output's name), is refused before any work; nothing changes.
TEST_F(CompareCli, RefusesOutputsThatClashBeforeAnyWork) {
  write_input("in.png", 200);
  const std::string in = path("in.png"), out = path("out");
  fs::create_directories(out + "/panel.png");
  const CliRun folder = run("compare " + in + " -o " + out + " --lens circle:100,100,50:2");
  EXPECT_EQ(folder.code, 2) << folder.err;
  EXPECT_EQ(std::count(folder.err.begin(), folder.err.end(), '\n'), 1) << folder.err;
  EXPECT_NE(folder.err.find("--output: '" + out + "/panel.png' is an existing folder"),
            std::string::npos)
      << folder.err;
  fs::remove(out + "/panel.png");
  const std::string polygon = "50 50\n150 50\n150 130\n50 130\n";
  std::ofstream(out + "/report.md") << polygon;
  const CliRun input = run("compare " + path("in.png") + " --lens polygon:" + out +
                           "/./report.md:2" + " -o " + out + "/");
  EXPECT_EQ(input.code, 2) << input.err;
  EXPECT_EQ(std::count(input.err.begin(), input.err.end(), '\n'), 1) << input.err;
  EXPECT_NE(input.err.find("would overwrite the --lens polygon file"), std::string::npos)
      << input.err;
  std::ifstream kept(out + "/report.md");
  std::stringstream text;
  text << kept.rdbuf();
  EXPECT_EQ(text.str(), polygon);
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 1);
}

TEST_F(CompareCli, HelpSucceeds) { EXPECT_EQ(run("compare --help").code, 0); }

}  // namespace
}  // namespace geolens
