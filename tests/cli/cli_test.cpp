// Runs the real `geolens` binary: exit codes, one-line errors, no partial outputs, the stats
// document, the identity at zoom 1, and the exported flattening checked by an independent ARAP.

#include "support/cli_test.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "geolens/io/image.h"
#include "support/arap_reference.h"

namespace geolens {
namespace {

namespace fs = std::filesystem;

using testing::CliRun;

class Cli : public testing::CliTest {
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
};

TEST_F(Cli, RejectsEveryBadInputWithOneLineAndExitTwo) {
  const std::string in = path("in.png"),
                    out = " -o " + path("out.png") + " --stats " + path("stats.json");
  expect_refused("magnify " + path("missing.png") + out + " --lens circle:50,50,20", "missing.png");
  {
    std::ofstream corrupt(path("corrupt.png"), std::ios::binary);
    corrupt << "\x89PNG\r\n\x1a\nthis is not a png at all";
  }
  expect_refused("magnify " + path("corrupt.png") + out + " --lens circle:50,50,20", "corrupt.png");
  expect_refused("magnify " + in + out + " --lens circle:50,50,0", "radius");
  expect_refused("magnify " + in + out + " --lens circle:50,50,-4", "radius");
  expect_refused("magnify " + in + out + " --lens circle:50,50,nan", "radius");
  expect_refused("magnify " + in + out + " --lens circle:50,50,1e-308",
                 "the circle reaches 1e-308 px from its centre, less than half a pixel");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20:0", "zoom");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20:-2", "zoom");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20:inf", "zoom");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20:9", "zoom");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --zoom 0.5", "zoom");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --alpha -0.1", "alpha");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --threads 100000",
                 "--threads: must be in [0, 1024], got 100000");
  // Devices and FIFOs are refused before they are read (an image path of /dev/zero filled the
  // memory, a FIFO hung).
  expect_refused("magnify /dev/zero" + out + " --lens circle:50,50,20",
                 "'/dev/zero' is not a regular file (a device or a FIFO)");
  ASSERT_EQ(::mkfifo(path("fifo.txt").c_str(), 0600), 0);
  expect_refused("magnify " + in + out + " --lens polygon:" + path("fifo.txt"),
                 "'" + path("fifo.txt") + "' is not a regular file (a device or a FIFO)");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --alpha nan", "alpha");
  expect_refused("magnify " + in + out + " --lens circle:300,50,20", "outside");
  expect_refused("magnify " + in + out + " --lens circle:50,-1,20", "outside");
  // Options out of range are named as the user wrote them, whichever part of the library checks.
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --mesh 3", "--mesh: must be");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --mesh 1001", "--mesh: must be");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --mesh-tolerance -1",
                 "--mesh-tolerance: must be");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --mesh-tolerance 1e-9",
                 "--mesh-tolerance: must be 0 (no refinement) or at least 0.01 pixels, got 1e-09");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --subdivide 9",
                 "--subdivide: must be in [0, 8]");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --extent-factor 0.5",
                 "--extent-factor: must be in (1, 100], got 0.5");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --max-iterations 0",
                 "--max-iterations: must be");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --footprint 1e308",
                 "--footprint: must be 0 (default) or in (zoom, 100] = (2, 100], got 1e+308");
  expect_refused("magnify " + in + " -o " + path("nowhere/out.png") + " --lens circle:50,50,20",
                 "nowhere");
  expect_refused("magnify " + in + " -o " + in + " --lens circle:50,50,20", "input");
  expect_refused("magnify " + in + " -o " + path("out.gif") + " --lens circle:50,50,20", "out.gif");
  expect_refused("magnify " + in + out + " --lens square:50,50,20", "circle:");
  expect_refused("magnify " + in + out, "--lens");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --profile cone", "cone");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --model ridge", "ridge");
  expect_refused("magnify " + in + out + " --lens circle:50,50,20 --size 0x10", "--size");
  // An image over the pixel limit is refused naming the limit and its option (256 x 192 here).
  expect_refused(
      "magnify " + in + out + " --lens circle:50,50,20 --max-pixels 49151",
      "256 x 192 pixels is more than the 49151 read (max_pixels; --max-pixels raises it)");
  for (const char* bad : {"0", "-3", "2.5", "1e20", "nan"})
    expect_refused("magnify " + in + out + " --lens circle:50,50,20 --max-pixels " + bad,
                   "--max-pixels: must be");
}

TEST_F(Cli, RejectsBadPolygonsAndMasks) {
  const std::string in = path("in.png"),
                    out = " -o " + path("out.png") + " --stats " + path("stats.json");
  auto polygon = [&](const std::string& name, const std::string& text) {
    std::ofstream(path(name)) << text;
    return " --lens polygon:" + path(name);
  };
  expect_refused("magnify " + in + out + polygon("two.txt", "10 10\n50 10\n"), "3");
  expect_refused("magnify " + in + out + polygon("flat.txt", "10 10\n50 10\n90 10\n"), "area");
  expect_refused("magnify " + in + out + polygon("bowtie.txt", "10 10\n90 90\n90 10\n20 60\n"),
                 "intersect");
  expect_refused("magnify " + in + out + polygon("outside.txt", "10 10\n400 10\n10 90\n"),
                 "outside");
  expect_refused("magnify " + in + out + polygon("words.txt", "10 10\nten 90\n90 10\n"),
                 "words.txt");
  expect_refused("magnify " + in + out + " --lens polygon:" + path("none.txt"), "none.txt");
  save_image(path("empty.png"), Image(256, 192, 1, 0));
  expect_refused("magnify " + in + out + " --lens mask:" + path("empty.png"), "non-zero");
  save_image(path("small.png"), Image(100, 100, 1, 255));
  expect_refused("magnify " + in + out + " --lens mask:" + path("small.png"), "100x100");
  expect_refused("magnify " + in + out + " --lens mask:" + path("none.png"), "none.png");
}

// Every output of a run is checked before any work: none is an existing folder, none names the
// same file as another (however spelled) or as any input (the image, polygon and mask files).
TEST_F(Cli, RefusesOutputsThatClashBeforeAnyWork) {
  const std::string in = path("in.png"), lens = " --lens circle:128,96,40";
  const std::string magnify = "magnify " + in + lens;
  fs::create_directories(path("folder.png"));
  fs::create_directories(path("folder.json"));
  expect_refused(magnify + " -o " + path("folder.png"),
                 "--output: '" + path("folder.png") + "' is an existing folder");
  expect_refused(magnify + " -o " + path("out.png") + " --stats " + path("folder.json"),
                 "--stats: '" + path("folder.json") + "' is an existing folder");
  expect_refused(magnify + " -o " + path("out.png") + " --before-after " + path("folder.png"),
                 "--before-after: '" + path("folder.png") + "' is an existing folder");
  expect_refused(magnify + " -o " + path("out.png") + " --stats " + path("out.png"),
                 "--stats: '" + path("out.png") + "' is the same file as --output");
  expect_refused(magnify + " -o " + path("out.png") + " --before-after " + path("./out.png"),
                 "--before-after: '" + path("./out.png") + "' is the same file as --output");
  expect_refused(magnify + " -o " + path("out.png") + " --export-mesh " + path("m") + " --stats " +
                     path("folder.json/../m_flat.obj"),
                 "is the same file as --export-mesh '" + path("m_flat.obj") + "'");
  {  // Relative to the working folder, where "out.png" and "./out.png" spell one new file.
    const fs::path cwd = fs::current_path();
    fs::current_path(dir_);
    expect_refused("magnify in.png" + lens + " -o out.png --before-after ./out.png",
                   "--before-after: './out.png' is the same file as --output 'out.png'");
    expect_refused("magnify in.png" + lens + " -o out.png --export-mesh m --stats m_3d.obj",
                   "--stats: 'm_3d.obj' is the same file as --export-mesh 'm_3d.obj'");
    expect_refused("magnify ./in.png" + lens + " -o in.png",
                   "--output: 'in.png' would overwrite the input './in.png'");
    fs::current_path(cwd);
  }
  expect_refused("magnify " + in + " -o " + path("./in.png") + lens,
                 "--output: '" + path("./in.png") + "' would overwrite the input");
  std::ofstream(path("poly.txt")) << "100 60\n160 60\n160 130\n100 130\n";
  std::ofstream(path("m_flat.obj")) << "100 60\n160 60\n160 130\n100 130\n";
  Image mask(256, 192, 1, 0);
  for (int y = 80; y < 110; ++y)
    for (int x = 110; x < 150; ++x) *mask.at(x, y) = 255;
  save_image(path("mask.png"), mask);
  expect_refused("magnify " + in + " -o " + path("mask.png") + " --lens mask:" + path("mask.png"),
                 "--output: '" + path("mask.png") + "' would overwrite the --lens mask file");
  expect_refused("magnify " + in + " -o " + path("out.png") + " --stats " + path("poly.txt") +
                     " --lens polygon:" + path("poly.txt"),
                 "--stats: '" + path("poly.txt") + "' would overwrite the --lens polygon file");
  expect_refused(
      "magnify " + in + " -o " + path("out.png") + " --export-mesh " + path("m") +
          " --lens polygon:" + path("m_flat.obj") + ":2",
      "--export-mesh: '" + path("m_flat.obj") + "' would overwrite the --lens polygon file");
}

// A run that fails after the work (here the stats cannot be written: nothing can be created in
// /proc, not even by root) leaves none of its outputs behind.
TEST_F(Cli, FailureAfterTheWorkLeavesNoOutput) {
  if (!fs::is_directory("/proc/self")) GTEST_SKIP() << "no /proc";
  const CliRun r = run("magnify " + path("in.png") + " -o " + path("out.png") + " --before-after " +
                       path("both.png") + " --export-mesh " + path("m") +
                       " --lens circle:128,96,30:1.5 --stats /proc/geolens_stats.json");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("geolens: failed: write_file: cannot write '/proc/geolens_stats"),
            std::string::npos)
      << r.err;
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir_)) left.push_back(entry.path().string());
  EXPECT_EQ(left.size(), 2u);  // in.png and stderr.txt
  for (const std::string& f : left)
    EXPECT_TRUE(f == path("in.png") || f == path("stderr.txt")) << f;
}

// Stopped by SIGTERM while it writes (here blocked on a FIFO given as its --output, which it
// writes into rather than replaces, with no reader yet), a run removes its temporary files, the
// --stats one already staged beside stats.json and the --output's in the temporary folder, and
// dies of the signal (exit 143 in the shell). A link given as an output writes the file it names.
TEST_F(Cli, InterruptedRunLeavesNoTemporaryAndLinksAreFollowed) {
  const std::string fifo = path("fifo.png");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string script = path("interrupt.sh");
  std::ofstream(script) << std::string(GEOLENS_CLI) + " magnify " + path("in.png") + " -o " + fifo +
                               " --stats " + path("stats.json") +
                               " --lens circle:128,96,30:1.5 2> /dev/null &\n"
                               "p=$!\n"
                               "for i in $(seq 600); do\n"
                               "  ls " +
                               path("stats.tmp-") +
                               "* > /dev/null 2>&1 && break\n"
                               "  sleep 0.05\n"
                               "done\n"
                               "sleep 0.2\n"
                               "kill -TERM $p\n"
                               "wait $p\n"
                               "echo $? > " +
                               path("code.txt") +
                               "\n"
                               "ls " +
                               fs::temp_directory_path().string() +
                               "/fifo.tmp-$p-* 2> /dev/null | wc -l > " + path("left.txt") + "\n";
  ASSERT_EQ(std::system(("sh " + script).c_str()), 0);
  std::string code, left;
  std::ifstream(path("code.txt")) >> code;
  std::ifstream(path("left.txt")) >> left;
  EXPECT_EQ(code, "143");
  EXPECT_EQ(left, "0");
  EXPECT_TRUE(fs::is_fifo(fifo));
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
  EXPECT_FALSE(fs::exists(path("stats.json")));

  std::ofstream(path("real.json")) << "old";
  fs::create_symlink("real.json", path("link.json"));
  const CliRun r = run("magnify " + path("in.png") + " -o " + path("out.png") + " --stats " +
                       path("link.json") + " --lens circle:128,96,30:1.5");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(path("link.json")));
  EXPECT_EQ(std::ifstream(path("real.json")).peek(), '{');  // the stats, not "old"
  fs::create_symlink("missing.json", path("dangling.json"));
  expect_refused(
      "magnify " + path("in.png") + " -o " + path("out2.png") + " --stats " +
          path("dangling.json") + " --lens circle:128,96,30:1.5",
      "--stats: '" + path("dangling.json") + "' is a symbolic link to a file that is missing");
}

// A run that succeeds writes every output, each where it was asked, and no temporary file.
TEST_F(Cli, SuccessfulRunWritesEveryOutput) {
  fs::create_directories(path("sub"));
  const CliRun r =
      run("magnify " + path("in.png") + " -o " + path("out.png") + " --before-after " +
          path("sub/both.jpg") + " --export-mesh " + path("sub/m") + " --stats " +
          path("stats.json") + " --lens circle:128,96,40 --mesh 40 --max-pixels 49152");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(load_image(path("out.png")).width, 256);
  EXPECT_EQ(load_image(path("sub/both.jpg")).width, 256 + 8 + 256);
  for (const char* name : {"sub/m_3d.obj", "sub/m_flat.obj", "stats.json"})
    EXPECT_GT(fs::file_size(path(name)), 0u) << name;
  for (const auto& entry : fs::recursive_directory_iterator(dir_))
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
  // What the run read: an image, framed at its size, scale 1.
  std::ifstream in(path("stats.json"));
  const nlohmann::json source = nlohmann::json::parse(in).at("source");
  EXPECT_EQ(source.at("kind"), "image");
  EXPECT_EQ(source.at("frame"), nlohmann::json({256, 192}));
  EXPECT_EQ(source.at("scale").get<double>(), 1.0);
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
  EXPECT_FALSE(s.at("distortion").at("degenerate").get<bool>());
  const auto& t = s.at("timings_ms");
  for (const char* stage : {"load", "lift", "texture", "factorize", "iterate", "solve", "measure",
                            "render", "save", "other", "total"})
    EXPECT_GE(t.at(stage).get<double>(), 0) << stage;
  // The total is the sum of its parts, loading and saving included; the solve holds its stages.
  double parts = 0;
  for (const char* part : {"load", "solve", "measure", "render", "save", "other"})
    parts += t.at(part).get<double>();
  EXPECT_NEAR(parts, t.at("total").get<double>(), 1e-9 * parts);
  EXPECT_GT(t.at("load").get<double>(), 0);
  EXPECT_GT(t.at("save").get<double>(), 0);
  EXPECT_LE(t.at("lift").get<double>() + t.at("iterate").get<double>(),
            t.at("solve").get<double>());
}

// An option the model does not read is warned about once and not echoed in the stats as if used;
// what it reads is echoed.
TEST_F(Cli, OptionsTheModelDoesNotReadAreWarnedAboutAndLeftOutOfTheStats) {
  const std::string common = "magnify " + path("in.png") + " -o " + path("out.png") +
                             " --lens circle:128,96,40:2 --mesh 40 --stats " + path("s.json");
  const CliRun focus = run(common + " --weights cotan --profile sphere --extent-factor 3");
  ASSERT_EQ(focus.code, 0) << focus.err;
  EXPECT_EQ(focus.err,
            "geolens: warning: --profile is ignored: the focus model magnifies the region "
            "uniformly; the profile shapes the lift's bump; it is left out of the stats\n"
            "geolens: warning: --extent-factor is ignored: the focus model solves its footprints "
            "only; it is left out of the stats\n"
            "geolens: warning: --weights is ignored: only the lift model flattens with other than "
            "cotan weights; it is left out of the stats\n");
  nlohmann::json s = nlohmann::json::parse(std::ifstream(path("s.json")));
  for (const char* unread : {"weights", "extent_factor", "texture", "alpha", "boundary"})
    EXPECT_FALSE(s.at("options").contains(unread)) << unread;
  EXPECT_EQ(s.at("options").at("mesh").get<int>(), 40);
  EXPECT_TRUE(s.at("options").contains("mesh_tolerance"));
  EXPECT_FALSE(s.at("lenses")[0].contains("profile"));
  EXPECT_TRUE(s.at("lenses")[0].contains("footprint"));

  const CliRun lift = run(common + " --model lift --weights cotan --footprint 5");
  ASSERT_EQ(lift.code, 0) << lift.err;
  EXPECT_NE(lift.err.find("--footprint is ignored: only the focus model has a footprint"),
            std::string::npos)
      << lift.err;
  EXPECT_EQ(lift.err.find("--weights"), std::string::npos) << lift.err;
  s = nlohmann::json::parse(std::ifstream(path("s.json")));
  EXPECT_EQ(s.at("options").at("weights"), "cotan");
  EXPECT_FALSE(s.at("options").contains("mesh_tolerance"));
  EXPECT_EQ(s.at("lenses")[0].at("profile"), "gaussian");
  EXPECT_FALSE(s.at("lenses")[0].contains("footprint"));
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
