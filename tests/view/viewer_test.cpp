// Runs the real geolens-view under Xvfb (Mesa's software OpenGL, one server per test program): its
// screenshots against each other and against the CPU renderer, scripted drags, mouse input and
// method switches, and its one-line refusals of bad input.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "geolens/io/image.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/render/annotate.h"
#include "geolens/render/render.h"
#include "geometry/polygon.h"
#include "support/scratch_folder.h"
#include "support/x_display.h"

namespace geolens {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 320, kHeight = 240;  // the image, and the window: one window pixel each

// The text of a file.
std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct ViewRun {
  int code = -1;
  std::string out, err;
};

class View : public testing::ScratchFolderTest {
 protected:
  void SetUp() override {
    ScratchFolderTest::SetUp();
    ASSERT_TRUE(display_) << "no X display (SetUpTestSuite failed)";
    // Smooth colour ramps under a fine checker and a few bars: enough detail that a moved or
    // magnified lens changes many pixels, smooth enough that sampling differences stay small.
    Image image(kWidth, kHeight, 3);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        uint8_t* p = image.at(x, y);
        const bool check = ((x / 8) + (y / 8)) % 2 == 0;
        p[0] = uint8_t(40 + 180 * x / kWidth);
        p[1] = uint8_t(40 + 180 * y / kHeight);
        p[2] = uint8_t(check ? 200 : 60);
        if (x % 40 < 4) p[0] = p[1] = p[2] = 20;
      }
    save_image(path("in.png"), image);
    source_ = image;
  }

  static void SetUpTestSuite() { display_ = std::make_unique<testing::XDisplay>(); }
  static void TearDownTestSuite() { display_.reset(); }

  // The environment that shows the viewer on the suite's Xvfb server.
  static std::string on_display() { return "DISPLAY=" + display_->name() + " "; }

  // Runs geolens-view `arguments` in `environment` (a prefix of the command), stdout and stderr
  // kept.
  ViewRun run(const std::string& arguments, const std::string& environment = on_display()) const {
    // Under AddressSanitizer (scripts/sanitize.sh) the viewer runs without leak checking: Mesa's
    // driver is unloaded at exit, so what its globals held looks leaked from an '<unknown
    // module>' that no suppression can name. Every other check stays on.
    const char* asan = std::getenv("ASAN_OPTIONS");
    const std::string env =
        asan ? "ASAN_OPTIONS='" + std::string(asan) + ":detect_leaks=0' " : std::string();
    const std::string command = env + environment + GEOLENS_VIEW + " " + arguments + " > " +
                                path("stdout.txt") + " 2> " + path("stderr.txt");
    ViewRun r;
    const int status = std::system(command.c_str());
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read_text(path("stdout.txt"));
    r.err = read_text(path("stderr.txt"));
    return r;
  }

  // A screenshot of in.png at the image's size with `arguments`, outlines off (a script).
  Image shot(const std::string& name, const std::string& arguments,
             const std::string& script_lines = "") {
    const std::string script = path(name + ".txt");
    std::ofstream(script) << "set outlines off\n"
                          << script_lines << "screenshot " << path(name) << "\nquit\n";
    const ViewRun r = run(path("in.png") + " --size " + std::to_string(kWidth) + "x" +
                          std::to_string(kHeight) + " --script " + script + " " + arguments);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    return load_image(path(name));
  }

  // Bad input: a non-zero exit `code` and exactly one line on stderr that mentions `mentions`.
  void expect_refused(const ViewRun& r, int code, const std::string& mentions) const {
    EXPECT_EQ(r.code, code) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("geolens-view: error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(mentions), std::string::npos) << r.err;
  }

  Image source_;
  static std::unique_ptr<testing::XDisplay> display_;
};

std::unique_ptr<testing::XDisplay> View::display_;

// Mean absolute difference over every channel of the pixels in [x0, x1) x [y0, y1).
double mean_difference(const Image& a, const Image& b, int x0 = 0, int y0 = 0, int x1 = kWidth,
                       int y1 = kHeight) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  double sum = 0;
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c, ++n) sum += std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c]));
  return sum / n;
}

// The "picture:" line of --stats: the triangles of the left pane's warp drawn as triangles (the
// others by the quad of the image in place) and all of them; the pictures drawn whole, in part
// and reused from the cache. -1 where the line is missing.
struct PictureStats {
  int moved = -1, triangles = -1, whole = -1, part = -1, reused = -1;
};

PictureStats picture_stats(const std::string& out) {
  PictureStats p;
  const size_t at = out.find("picture: ");
  if (at != std::string::npos)
    std::sscanf(out.c_str() + at,
                "picture: %d of %d triangles drawn as triangles (the rest as one quad); pictures "
                "drawn whole %d, in part %d, reused %d",
                &p.moved, &p.triangles, &p.whole, &p.part, &p.reused);
  return p;
}

TEST(ViewSetup, XvfbIsInstalled) {
  // scripts/setup.sh installs it; without it every test here would fail for that reason alone.
  ASSERT_EQ(std::system("command -v Xvfb > /dev/null"), 0)
      << "Xvfb is missing: install the xvfb package (bash scripts/setup.sh)";
}

TEST_F(View, TheScreenshotShowsTheImage) {
  const Image a = shot("a.png", "");
  ASSERT_EQ(a.width, kWidth);
  ASSERT_EQ(a.height, kHeight);
  // No lens: the window shows the image one window pixel per source pixel.
  EXPECT_LT(mean_difference(a, source_), 1.0);
}

TEST_F(View, AZoomedLensChangesItsRegionAndNothingBeyondItsFootprint) {
  const Image flat = shot("flat.png", "--lens circle:160,120,24:1");
  const Image zoomed = shot("zoomed.png", "--lens circle:160,120,24:2.5");
  EXPECT_LT(mean_difference(flat, source_), 1.0);  // zoom 1: the identity
  EXPECT_GT(mean_difference(zoomed, flat, 136, 96, 184, 144), 20.0);
  // The footprint (radius 2 x 2.5 x 24 = 120) reaches x = 40 .. 280: the side bands stay.
  EXPECT_LT(mean_difference(zoomed, flat, 0, 0, 30, kHeight), 0.5);
  EXPECT_LT(mean_difference(zoomed, flat, 290, 0, kWidth, kHeight), 0.5);
}

TEST_F(View, TheGpuPictureMatchesTheCpuRenderer) {
  for (const std::string model : {"focus", "lift"}) {
    SCOPED_TRACE(model);
    const Image gpu = shot(model + ".png", "--lens circle:150,110,30:2.5 --model " + model);
    LensOptions options;
    options.model = parse_lens_model(model);
    const LensResult result =
        GeometricLens(kWidth, kHeight, options).solve({Lens{Region::circle({150, 110}, 30), 2.5}});
    RenderOptions size;
    size.width = kWidth;
    size.height = kHeight;
    const Image cpu = render(result.warp, MipPyramid(source_), size);
    EXPECT_LT(mean_difference(gpu, cpu), 2.0);
    EXPECT_GT(mean_difference(gpu, source_), 5.0);  // and the lens is there
  }
}

TEST_F(View, AScriptedDragMovesTheLens) {
  const Image before = shot("before.png", "--lens circle:100,120,24:2.5");
  const Image dragged =
      shot("dragged.png", "--lens circle:100,120,24:2.5", "drag 1 220 100 12\nframe 14 wait\n");
  const Image placed = shot("placed.png", "--lens circle:220,100,24:2.5");
  EXPECT_GT(mean_difference(dragged, before), 5.0);
  EXPECT_LT(mean_difference(dragged, placed), 1.0);  // it ends where the drag ended
}

// The rows of a --frame-log: per frame that showed a new solve, per lens its place and zooms.
struct FrameRow {
  int frame = 0, lens = 0;
  double x = 0, y = 0, asked = 0, got = 0;
};

std::vector<FrameRow> frame_rows(const std::string& text) {
  std::vector<FrameRow> rows;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);  // the header
  while (std::getline(in, line)) {
    FrameRow r;
    int draft = 0;
    if (std::sscanf(line.c_str(), "%d,%d,%lf,%lf,%lf,%lf,%d", &r.frame, &r.lens, &r.x, &r.y,
                    &r.asked, &r.got, &draft) == 7)
      rows.push_back(r);
  }
  return rows;
}

// Dragged frame by frame, 1 source pixel a frame, as the viewer shows it (drafts while the lens
// moves, the full mesh once it rests): a circle dragged to and across the top side gets its zoom
// in every frame shown (its magnified focus slides away from the side), and one dragged along
// the side, 6 px below it, from near a corner to near the other, gets a zoom that changes by at
// most 0.03 a pixel between frames and is its own where the corners leave it the room; one
// dragged along it into a corner keeps a continuous zoom.
TEST_F(View, ADragToAlongAndAcrossASideShowsAContinuousZoom) {
  auto drag = [&](const std::string& name, const std::string& lens, const std::string& to,
                  int steps) {
    const std::string script = path(name + ".txt"), log = path(name + ".csv");
    // Frames show a solve of their own as solves finish, fewer on a loaded machine or a
    // sanitizer's slow build; every 10th frame waits for the solver, so at least one frame in 10
    // shows the place the drag has reached, however slow the machine.
    std::ofstream out(script);
    out << "drag 1 " << to << " " << steps << "\n";
    for (int frame = 10; frame <= steps + 10; frame += 10) out << "frame " << frame << " wait\n";
    out << "quit\n";
    out.close();
    const ViewRun r = run(path("in.png") + " --size 320x240 --lens " + lens + " --script " +
                          script + " --frame-log " + log);
    EXPECT_EQ(r.code, 0) << r.err;
    const std::vector<FrameRow> rows = frame_rows(read_text(log));
    EXPECT_GE(rows.size(), size_t(steps / 10));
    return rows;
  };
  const std::vector<FrameRow> across = drag("across", "circle:160,120,24:3", "160 0", 120);
  ASSERT_FALSE(across.empty());
  EXPECT_EQ(across.back().y, 0);
  for (const FrameRow& r : across) EXPECT_NEAR(r.got, 3, 1e-9) << "frame " << r.frame;
  const std::vector<FrameRow> along = drag("along", "circle:60,30,24:3", "260 30", 200);
  bool full = false;
  for (size_t k = 1; k < along.size(); ++k) {
    const FrameRow &a = along[k - 1], &b = along[k];
    EXPECT_LE(std::abs(b.got - a.got), 0.03 * std::abs(b.x - a.x) + 1e-9) << "frame " << b.frame;
    EXPECT_LE(b.got, b.asked);
    full = full || b.got == b.asked;
  }
  EXPECT_TRUE(full);
  // Along the top side into the corner, until it touches the left side: magnified about the
  // corner near it, never below 1.5 (it fell to 1.0), at most 0.3 a pixel, 3 touching.
  const std::vector<FrameRow> into = drag("into", "circle:120,30,24:3", "24 30", 96);
  ASSERT_FALSE(into.empty());
  for (size_t k = 1; k < into.size(); ++k) {
    const FrameRow &a = into[k - 1], &b = into[k];
    EXPECT_GE(b.got, 1.5) << "frame " << b.frame;
    EXPECT_LE(std::abs(b.got - a.got), 0.3 * std::abs(b.x - a.x) + 1e-9) << "frame " << b.frame;
  }
  EXPECT_EQ(into.back().x, 24);
  EXPECT_NEAR(into.back().got, 3, 1e-9);
}

// Dragged past another lens, 1 source pixel a frame, 40 px below it: the two share the room
// between them and are magnified as one where that gives both more, so neither is switched off
// (both at least 1.5 in every frame shown; the two as one, where their mesh did not hold their
// ring, got 1.13), and the zoom changes by at most 0.3 a pixel (the largest step, where the mesh
// stops holding the two as one, 0.25).
TEST_F(View, ADragPastAnotherLensNeverSwitchesEitherOff) {
  const std::string script = path("past.txt"), log = path("past.csv");
  std::ofstream out(script);
  out << "drag 1 280 160 240\n";
  for (int frame = 10; frame <= 250; frame += 10) out << "frame " << frame << " wait\n";
  out << "quit\n";
  out.close();
  const ViewRun r = run(path("in.png") +
                        " --size 320x240 --lens circle:40,160,24:2 --lens circle:160,120,24:2 "
                        "--script " +
                        script + " --frame-log " + log);
  ASSERT_EQ(r.code, 0) << r.err;
  // Per frame shown: where lens 1 is, and the zooms the two get.
  std::map<int, std::array<double, 3>> frames;
  for (const FrameRow& row : frame_rows(read_text(log))) {
    ASSERT_TRUE(row.lens == 1 || row.lens == 2) << row.lens;
    if (row.lens == 1) frames[row.frame][0] = row.x;
    frames[row.frame][size_t(row.lens)] = row.got;
  }
  ASSERT_GE(frames.size(), size_t(24));
  const std::array<double, 3>* before = nullptr;
  for (const auto& [frame, now] : frames) {
    for (size_t k : {1, 2}) {
      EXPECT_GE(now[k], 1.5) << "frame " << frame << " lens " << k;
      if (before)
        EXPECT_LE(std::abs(now[k] - (*before)[k]),
                  0.3 * std::max(1.0, std::abs(now[0] - (*before)[0])))
            << "frame " << frame << " lens " << k;
    }
    before = &now;
  }
  EXPECT_EQ(frames.rbegin()->second[0], 280);
  // At the end lens 2 has its room again; lens 1, 16 px from the right side, is held by it.
  EXPECT_NEAR(frames.rbegin()->second[2], 2, 1e-9);
}

TEST_F(View, TheMouseDragsZoomsAddsAndRemovesLenses) {
  const std::string lens = "--lens circle:100,120,24:2 ";
  // Dragged by 60, -20 window pixels (= source pixels here) with the left button.
  const Image dragged = shot("dragged.png", lens,
                             "mouse 100 120\npress left\nframe 1 mouse 130 110\nframe 2 mouse "
                             "160 100\nrelease left\nwait\n");
  EXPECT_LT(mean_difference(dragged, shot("placed.png", "--lens circle:160,100,24:2")), 1.0);
  // Two wheel steps over the lens: zoom + 0.5.
  const Image wheeled = shot("wheeled.png", lens, "mouse 100 120\nscroll 2\n");
  EXPECT_LT(mean_difference(wheeled, shot("zoom.png", "--lens circle:100,120,24:2.5")), 1.0);
  // Shift + wheel: the radius x 1.1.
  const Image widened = shot("widened.png", lens, "mouse 100 120\nscroll 1 shift\n");
  EXPECT_LT(mean_difference(widened, shot("wide.png", "--lens circle:100,120,26.4:2")), 1.0);
  // Ctrl + click adds a circle (radius 0.08 x 240 = 19.2, zoom 2) where the pointer is.
  const Image added = shot("added.png", "", "mouse 200 90\npress left ctrl\nrelease left\n");
  EXPECT_LT(mean_difference(added, shot("one.png", "--lens circle:200,90,19.2:2")), 1.0);
  // A click selects, Delete removes.
  const Image removed = shot("removed.png", lens,
                             "mouse 100 120\npress left\nrelease left\n"
                             "key delete\n");
  EXPECT_LT(mean_difference(removed, source_), 1.0);
}

TEST_F(View, APolygonDrawnWithTheMouseIsOutlinedThenCancelledByEscape) {
  // Three vertices clicked, the pointer further on: the outline (drawn with the UI, so in a
  // "panel" screenshot even with the panel off) crosses the picture; Escape removes it, and no
  // lens was made.
  std::ofstream(path("draw.txt")) << "set outlines off\nset panel off\nkey polygon\n"
                                     "mouse 60 60\npress left\nrelease left\n"
                                     "mouse 260 60\npress left\nrelease left\n"
                                     "mouse 260 180\npress left\nrelease left\n"
                                     "mouse 60 180\n"
                                  << "screenshot " << path("drawing.png") << " panel\n"
                                  << "frame 1 key escape\n"
                                  << "screenshot " << path("cancelled.png") << " panel\nquit\n";
  const ViewRun r = run(path("in.png") + " --size 320x240 --script " + path("draw.txt"));
  ASSERT_EQ(r.code, 0) << r.err;
  const Image drawing = load_image(path("drawing.png"));
  const Image cancelled = load_image(path("cancelled.png"));
  EXPECT_LT(mean_difference(cancelled, source_), 1.0);
  // Along the top edge (y = 60) and the edge on to the pointer (x = 260 .. 60 at y = 180).
  EXPECT_GT(mean_difference(drawing, source_, 80, 57, 240, 64), 40.0);
  EXPECT_GT(mean_difference(drawing, source_, 80, 177, 240, 184), 40.0);
  // Away from the edges nothing is drawn.
  EXPECT_LT(mean_difference(drawing, source_, 100, 90, 220, 150), 0.5);
}

TEST_F(View, APolygonDrawnByScriptIsMagnifiedAndExportedAsAPolygonLens) {
  // Window pixels are source pixels here.
  const Image drawn =
      shot("drawn.png", "",
           "polygon 130 90 200 100 190 160 120 150\nexport " + path("lenses.txt") + "\n");
  EXPECT_GT(mean_difference(drawn, source_, 120, 90, 200, 160), 10.0);
  const std::string arguments = read_text(path("lenses.txt"));
  const std::string polygon = path("lenses-lens-1.txt");
  EXPECT_NE(arguments.find("--lens polygon:" + polygon + ":2"), std::string::npos) << arguments;
  const std::vector<Eigen::Vector2d> vertices = read_polygon_file(polygon);
  ASSERT_EQ(vertices.size(), 4u);
  const double clicked[4][2] = {{130, 90}, {200, 100}, {190, 160}, {120, 150}};
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(vertices[i].x(), clicked[i][0], 0.01) << i;
    EXPECT_NEAR(vertices[i].y(), clicked[i][1], 0.01) << i;
  }
  // The exported arguments reproduce the view.
  std::string line = arguments.substr(0, arguments.find('\n'));
  EXPECT_LT(mean_difference(shot("again.png", line), drawn), 1.0);
}

// With outlines on, a polygon lens is outlined where the picture shows its boundary: white
// pixels along the magnified polygon, none elsewhere.
TEST_F(View, APolygonLensIsOutlinedWhereThePictureShowsIt) {
  std::ofstream(path("square.txt")) << "140 100\n180 100\n180 140\n140 140\n";
  const std::string lens = "--lens polygon:" + path("square.txt") + ":2 ";
  // Overlays are drawn with the panel's user interface: a "panel" screenshot, the panel hidden.
  auto overlaid = [&](const std::string& name, const char* outlines) {
    std::ofstream(path(name + ".txt"))
        << "set panel off\nset outlines " << outlines << "\nscreenshot " << path(name + ".png")
        << " panel\nquit\n";
    const ViewRun r =
        run(path("in.png") + " --size 320x240 " + lens + "--script " + path(name + ".txt"));
    EXPECT_EQ(r.code, 0) << r.err;
    return load_image(path(name + ".png"));
  };
  const Image off = overlaid("off", "off");
  const Image on = overlaid("on", "on");
  // The square magnified 2x about its centre (160, 120): sides at x, y = 160 -+ 40, 120 -+ 40.
  int near_side = 0, elsewhere = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const uint8_t* p = on.at(x, y);
      const uint8_t* q = off.at(x, y);
      const bool white = p[0] > 240 && p[1] > 240 && p[2] > 240 &&
                         std::abs(int(p[0]) - int(q[0])) + std::abs(int(p[2]) - int(q[2])) > 60;
      if (!white) continue;
      const double dx = std::min(std::abs(x + 0.5 - 120), std::abs(x + 0.5 - 200));
      const double dy = std::min(std::abs(y + 0.5 - 80), std::abs(y + 0.5 - 160));
      const bool on_side = (dx < 3 && y > 76 && y < 164) || (dy < 3 && x > 116 && x < 204);
      (on_side ? near_side : elsewhere)++;
    }
  EXPECT_GT(near_side, 4 * 60);  // most of the 320 px of outline
  EXPECT_EQ(elsewhere, 0);
}

TEST_F(View, TheHeatmapColoursShapeDistortionWithTheColoursOfCompare) {
  const std::string lens = "--lens circle:160,120,24:2.5 ";
  const Image heat = shot("heat.png", lens, "set heatmap on\n");
  // Every pixel as heatmap() (annotate.h) draws a distortion of 0: 0.75 x heat_colour(0) over
  // the luminance.
  Image zero(kWidth, kHeight, 3);
  const std::array<uint8_t, 3> blue = heat_colour(0);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const uint8_t* p = source_.at(x, y);
      const double grey = 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
      for (int c = 0; c < 3; ++c)
        zero.at(x, y)[c] = uint8_t(std::lround(0.75 * blue[c] + 0.25 * grey));
    }
  // Beyond the footprint (x < 40, x >= 280) the warp is the identity, distortion 0; within it,
  // around the focus, the context is distorted: other colours.
  EXPECT_LT(mean_difference(heat, zero, 0, 0, 30, kHeight), 1.5);
  EXPECT_LT(mean_difference(heat, zero, 290, 0, kWidth, kHeight), 1.5);
  EXPECT_GT(mean_difference(heat, zero, 80, 60, 240, 180), 15.0);
  // Off again: the picture.
  const Image off = shot("off.png", lens, "key heatmap\nkey heatmap\n");
  EXPECT_LT(mean_difference(off, shot("plain.png", lens)), 0.5);
}

// A frame with nothing new copies the cached picture; a new warp or outline redraws it where
// they change, a new view or overlay all of it. Each picture is the one drawn afresh (--redraw),
// but for a few pixels where Mesa rasterizes a texture by other rules than the window (a
// wireframe's lines move by a pixel in places).
TEST_F(View, TheCachedPictureIsTheOneDrawnAfresh) {
  const std::string shots[] = {"moved", "selected", "zoomed", "heat", "wire", "split", "panel"};
  auto script = [&](const std::string& mode) {
    const std::string name = path(mode + ".txt");
    std::ofstream(name) << "add circle:250,60,16:2\nwait\nframe 1 move 1 200 150\nwait\n"
                        << "frame 2 screenshot " << path(mode + "-moved.png") << "\n"
                        << "frame 3 select 2\nframe 4 screenshot " << path(mode + "-selected.png")
                        << "\nframe 5 move 2 240 80\nwait\nframe 6 mouse 40 200\nscroll 1\n"
                        << "frame 7 screenshot " << path(mode + "-zoomed.png") << "\n"
                        << "frame 8 set heatmap on\nscreenshot " << path(mode + "-heat.png") << "\n"
                        << "frame 9 set heatmap off\nset wireframe on\nscreenshot "
                        << path(mode + "-wire.png") << "\n"
                        << "frame 10 set wireframe off\nmove 1 150 110\nset split fisheye\nwait\n"
                        << "frame 11 screenshot " << path(mode + "-split.png") << "\n"
                        << "frame 12 move 1 170 120\nwait\nscreenshot " << path(mode + "-panel.png")
                        << " panel\nframe 20 quit\n";
    return name;
  };
  const std::string common =
      path("in.png") + " --size 320x240 --lens circle:100,120,24:2.5 --stats ";
  const ViewRun cached = run(common + "--script " + script("cached"));
  ASSERT_EQ(cached.code, 0) << cached.err;
  const ViewRun fresh = run(common + "--redraw --script " + script("fresh"));
  ASSERT_EQ(fresh.code, 0) << fresh.err;
  for (const std::string& shot : shots) {
    SCOPED_TRACE(shot);
    const Image a = load_image(path("cached-" + shot + ".png"));
    const Image b = load_image(path("fresh-" + shot + ".png"));
    EXPECT_LT(mean_difference(a, b), shot == "wire" ? 0.5 : 0.02);
    if (shot == "moved") EXPECT_GT(mean_difference(a, source_), 5.0);  // a lens is there
  }
  // The moves and the selection redrew in part; the frames between them were copies.
  const PictureStats c = picture_stats(cached.out), f = picture_stats(fresh.out);
  EXPECT_GE(c.part, 2) << cached.out;
  EXPECT_GE(c.reused, 5) << cached.out;
  EXPECT_EQ(f.whole + f.part + f.reused, 0) << fresh.out;
}

// A still view is drawn once: every later frame is the cached picture.
TEST_F(View, AStillViewIsDrawnOnce) {
  std::ofstream(path("still.txt")) << "wait\nframe 20 quit\n";
  const ViewRun r = run(path("in.png") + " --size 320x240 --lens circle:100,120,24:2.5 --stats " +
                        "--script " + path("still.txt"));
  ASSERT_EQ(r.code, 0) << r.err;
  const PictureStats p = picture_stats(r.out);
  EXPECT_EQ(p.whole, 1) << r.out;
  EXPECT_EQ(p.part, 0) << r.out;
  EXPECT_GE(p.reused, 19) << r.out;
}

// The image in place is one quad: a focus lens's triangles beyond its footprint are not drawn as
// triangles, a zoom-1 lens's none; a global lift moves every vertex, so every triangle is drawn.
TEST_F(View, OnlyTheTrianglesThatMoveAreDrawnAsTriangles) {
  auto stats = [&](const std::string& arguments) {
    const ViewRun r = run(path("in.png") + " --size 320x240 --stats --frames 1 --screenshot " +
                          path("s.png") + " " + arguments);
    EXPECT_EQ(r.code, 0) << r.err;
    const PictureStats p = picture_stats(r.out);
    EXPECT_GT(p.triangles, 0) << r.out;
    return p;
  };
  EXPECT_EQ(stats("--lens circle:160,120,24:1").moved, 0);
  const PictureStats focus = stats("--lens circle:60,60,10:2");
  EXPECT_GT(focus.moved, 0);
  EXPECT_LT(focus.moved, focus.triangles);
  const PictureStats lift = stats("--lens circle:160,120,24:2.5 --model lift");
  EXPECT_EQ(lift.moved, lift.triangles);
}

TEST_F(View, TheSplitViewShowsBothMethodsOnTheSameLenses) {
  // A window twice the image's width: each half shows the image one window pixel per source
  // pixel, the left through the geometric lens, the right through the fisheye lens.
  const std::string lens = " --lens circle:160,120,24:2.5";
  std::ofstream(path("split.txt"))
      << "set outlines off\nscreenshot " << path("split.png") << "\nquit\n";
  const ViewRun r =
      run(path("in.png") + " --size 640x240 --split fisheye --script " + path("split.txt") + lens);
  ASSERT_EQ(r.code, 0) << r.err;
  const Image split = load_image(path("split.png"));
  ASSERT_EQ(split.width, 2 * kWidth);
  Image left(kWidth, kHeight, 3), right(kWidth, kHeight, 3);
  for (int y = 0; y < kHeight; ++y) {
    std::copy_n(split.at(0, y), kWidth * 3, left.at(0, y));
    std::copy_n(split.at(kWidth, y), kWidth * 3, right.at(0, y));
  }
  // The halves differ where the lens is, not far from it; each is its method alone.
  EXPECT_GT(mean_difference(left, right, 100, 60, 220, 180), 2.0);
  EXPECT_LT(mean_difference(left, right, 0, 0, 30, kHeight), 0.5);
  EXPECT_LT(mean_difference(left, shot("geometric.png", lens)), 0.5);
  EXPECT_LT(mean_difference(right, shot("fisheye.png", lens + " --method fisheye")), 0.5);
}

// Switching the split's method and adding lenses: once solved, the right half is the named
// method's picture of the current lenses, never the last method's or the old lenses'; where the
// method refuses the lenses (classic disks that overlap), the image as it is.
TEST_F(View, TheSplitShowsTheNamedMethodOfTheCurrentLenses) {
  const std::string lens = " --lens circle:60,120,16:2", far = " --lens circle:260,120,12:2";
  std::ofstream(path("switch.txt"))
      << "set outlines off\nscreenshot " << path("fisheye.png")
      << "\nframe 2 set split bifocal\nscreenshot " << path("bifocal.png")
      << "\nframe 4 add circle:260,120,12:2\nscreenshot " << path("added.png")
      << "\nframe 6 add circle:100,120,12:2\nscreenshot " << path("overlap.png") << "\nquit\n";
  const ViewRun r =
      run(path("in.png") + " --size 640x240 --split fisheye --script " + path("switch.txt") + lens);
  ASSERT_EQ(r.code, 0) << r.err;
  auto right = [&](const std::string& name) {
    const Image both = load_image(path(name));
    Image half(kWidth, kHeight, 3);
    for (int y = 0; y < kHeight; ++y) std::copy_n(both.at(kWidth, y), kWidth * 3, half.at(0, y));
    return half;
  };
  const Image fisheye = shot("f.png", lens + " --method fisheye");
  const Image bifocal = shot("b.png", lens + " --method bifocal");
  const Image added = shot("a.png", lens + far + " --method bifocal");
  EXPECT_GT(mean_difference(fisheye, bifocal, 20, 80, 100, 160), 1.0);  // they differ there
  EXPECT_GT(mean_difference(bifocal, added, 220, 80, 300, 160), 1.0);
  EXPECT_LT(mean_difference(right("fisheye.png"), fisheye), 0.5);
  EXPECT_LT(mean_difference(right("bifocal.png"), bifocal), 0.5);
  EXPECT_LT(mean_difference(right("added.png"), added), 0.5);
  EXPECT_LT(mean_difference(right("overlap.png"), source_), 1.0);
}

TEST_F(View, StatsReportTheStagesTheLibraryTimed) {
  const std::string arguments = path("in.png") + " --size 320x240 --stats --frames 2 " +
                                "--lens circle:160,120,24:2.5 --screenshot " + path("s.png");
  const ViewRun geometric = run(arguments + " --model lift");
  ASSERT_EQ(geometric.code, 0) << geometric.err;
  double solve = 0, lift = 0, texture = 0, factorize = 0, iterate = 0, total = 0;
  int solves = 0;
  const size_t at = geometric.out.find("solve (last) ");
  ASSERT_NE(at, std::string::npos) << geometric.out;
  ASSERT_EQ(std::sscanf(geometric.out.c_str() + at, "solve (last) %lf", &solve), 1);
  const size_t stages = geometric.out.find("stages of the last solve");
  ASSERT_NE(stages, std::string::npos) << geometric.out;
  ASSERT_EQ(std::sscanf(geometric.out.c_str() + stages,
                        "stages of the last solve (calibration solves: %d): lift %lf ms, texture "
                        "%lf ms, factorize %lf ms, iterate %lf ms, total %lf ms",
                        &solves, &lift, &texture, &factorize, &iterate, &total),
            6)
      << geometric.out;
  // The lift model calibrates its heights: several solves, each with every stage; the stages
  // are parts of the total, which is part of the solve the worker timed.
  EXPECT_GE(solves, 1);
  EXPECT_GT(iterate, 0);
  EXPECT_GT(total, 0);
  EXPECT_LE(lift + texture + factorize + iterate, total * 1.001 + 0.01);
  EXPECT_LE(total, solve * 1.001 + 0.01);
  // An image that fits is uploaded whole.
  EXPECT_NE(geometric.out.find("texture: level 0 of the image, 320 x 240 texels"),
            std::string::npos)
      << geometric.out;
  // A plain image has no detail finer than its pixels: none is rendered.
  EXPECT_NE(geometric.out.find("detail: none shown (the source has none)"), std::string::npos)
      << geometric.out;
  // A classic lens has no stages, and none are made up for it.
  const ViewRun classic = run(arguments + " --method fisheye");
  ASSERT_EQ(classic.code, 0) << classic.err;
  EXPECT_NE(classic.out.find("stages: none (fisheye)"), std::string::npos) << classic.out;
}

TEST_F(View, AnImageOf16384By16384PixelsOpensAndIsMagnified) {
  // Grey squares of 1024 source pixels, 50 and 200: 32 window pixels each in a 512 x 512 window.
  constexpr int kSide = 16384, kSquare = 1024, kWindow = 512;
  const auto square = [&](double x, double y) {
    return (int(x) / kSquare + int(y) / kSquare) % 2 == 0 ? 200 : 50;
  };
  {
    Image big(kSide, kSide, 1);
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) big.at(x, y)[0] = uint8_t(square(x, y));
    save_image(path("big.png"), big);
  }
  // A zoom-2.5 lens of radius 1024 at the centre.
  const ViewRun r = run(path("big.png") + " --size 512x512 --lens circle:8192,8192,1024:2.5 " +
                        "--stats --screenshot " + path("big_shot.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  // Not the whole image on the GPU: the finest level of its pyramid within 8192 texels a side.
  EXPECT_NE(r.out.find("texture: level 1 of the image, 8192 x 8192 texels"), std::string::npos)
      << r.out;
  const Image shot = load_image(path("big_shot.png"));
  ASSERT_EQ(shot.width, kWindow);
  // Window pixel (i, j) shows source ((i, j) + 0.5) x 32 beyond the lens, and at 1 / 2.5 of its
  // distance from the centre within the focus (radius 1024 x 2.5 = 2560 source pixels shown,
  // 80 window pixels). Pixels near a square's edge there are skipped.
  const double per_pixel = double(kSide) / kWindow, centre = kWindow / 2.0;
  int checked_out = 0, checked_in = 0;
  for (int j = 0; j < kWindow; j += 3)
    for (int i = 0; i < kWindow; i += 3) {
      const double dx = i + 0.5 - centre, dy = j + 0.5 - centre, d = std::hypot(dx, dy);
      double x = 0, y = 0;
      if (d > 200) {  // beyond the footprint (2 x 2.5 x 1024 source pixels = 160 window pixels)
        x = (i + 0.5) * per_pixel;
        y = (j + 0.5) * per_pixel;
        ++checked_out;
      } else if (d < 70) {
        x = kSide / 2.0 + dx * per_pixel / 2.5;
        y = kSide / 2.0 + dy * per_pixel / 2.5;
        ++checked_in;
      } else {
        continue;
      }
      const double margin = 2 * per_pixel / (d < 70 ? 2.5 : 1);  // two window pixels
      const auto near_edge = [&](double v) {
        const double m = std::fmod(v, kSquare);
        return m < margin || m > kSquare - margin;
      };
      if (near_edge(x) || near_edge(y)) continue;
      EXPECT_NEAR(shot.at(i, j)[0], square(x, y), 4) << i << ", " << j;
    }
  EXPECT_GT(checked_out, 1000);
  EXPECT_GT(checked_in, 100);
}

TEST_F(View, SwitchingToAClassicLensChangesThePicture) {
  const std::string lens = "--lens circle:160,120,24:2.5 ";
  const Image geometric = shot("geometric.png", lens);
  const Image fisheye = shot("fisheye.png", lens, "set method fisheye\n");
  EXPECT_GT(mean_difference(fisheye, geometric), 2.0);
  // The same as starting with it.
  EXPECT_LT(mean_difference(fisheye, shot("direct.png", lens + "--method fisheye")), 0.5);
}

// A mesh opens as its rendered view, with lenses on it; the arrow keys' orbit turns the camera and
// renders it again, the lens staying where it is on the screen; on an image orbit does nothing.
TEST_F(View, AMeshOpensAndOrbitsUnderItsLens) {
  // A box, 2 x 1 x 0.5, its faces lit differently as it turns.
  std::ofstream(path("box.obj"))
      << "v -1 -0.5 -0.25\nv 1 -0.5 -0.25\nv 1 0.5 -0.25\nv -1 0.5 -0.25\n"
         "v -1 -0.5 0.25\nv 1 -0.5 0.25\nv 1 0.5 0.25\nv -1 0.5 0.25\n"
         "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n"
         "f 4 1 5 8\n";
  auto view = [&](const std::string& input, const std::string& name, const std::string& lines,
                  const std::string& lens = "circle:512,512,100:2") {
    std::ofstream(path(name + ".txt"))
        << "set outlines off\n"
        << lines << "screenshot " << path(name + ".png") << "\nquit\n";
    const ViewRun r =
        run(input + " --size 320x240 --lens " + lens + " --script " + path(name + ".txt"));
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    return load_image(path(name + ".png"));
  };
  const Image front = view(path("box.obj"), "front", "");
  const Image turned = view(path("box.obj"), "turned", "orbit 90 0\nwait\n");
  const Image back = view(path("box.obj"), "back", "orbit 90 0\nwait\norbit -90 0\nwait\n");
  EXPECT_GT(mean_difference(turned, front), 5.0);
  EXPECT_LT(mean_difference(back, front), 0.5);  // the same camera, the same lens
  // An image has no camera: the orbit changes nothing.
  const std::string lens = "circle:160,120,24:2.5";
  EXPECT_LT(mean_difference(view(path("in.png"), "image", "orbit 90 0\nwait\n", lens),
                            view(path("in.png"), "still", "", lens)),
            0.5);
}

// An orbit renders the new view off the UI thread: presses made before it is shown add up and only
// the newest camera is shown; a screenshot, as 'wait', waits for it; --stats counts it.
TEST_F(View, AnOrbitRendersOffTheUiThreadAndTheNewestCameraWins) {
  std::ofstream(path("box.obj"))
      << "v -1 -0.5 -0.25\nv 1 -0.5 -0.25\nv 1 0.5 -0.25\nv -1 0.5 -0.25\n"
         "v -1 -0.5 0.25\nv 1 -0.5 0.25\nv 1 0.5 0.25\nv -1 0.5 0.25\n"
         "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n"
         "f 4 1 5 8\n";
  auto view = [&](const std::string& name, const std::string& lines) {
    std::ofstream(path(name + ".txt"))
        << "set outlines off\n"
        << lines << "screenshot " << path(name + ".png") << "\nquit\n";
    ViewRun r =
        run(path("box.obj") + " --size 320x240 --lens circle:512,512,100:2 --stats --script " +
            path(name + ".txt"));
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    return std::make_pair(load_image(path(name + ".png")), r.out);
  };
  const auto [front, front_out] = view("front", "");
  const auto [turned, turned_out] = view("turned", "orbit 90 0\nwait\n");
  // Three presses in one frame: one view shown, the three turns added up.
  const auto [pressed, pressed_out] = view("pressed", "orbit 30 0\norbit 30 0\norbit 30 0\n");
  // Pressed over several frames, the screenshot (no 'wait') still shows the last camera.
  const auto [later, later_out] =
      view("later", "orbit 45 0\nframe 2 orbit 45 0\nframe 3 orbit 0 0\n");
  EXPECT_GT(mean_difference(turned, front), 5.0);
  EXPECT_LT(mean_difference(pressed, turned), 0.5);
  EXPECT_LT(mean_difference(later, turned), 0.5);
  EXPECT_NE(front_out.find("opened: 0 files or views"), std::string::npos) << front_out;
  EXPECT_NE(turned_out.find("opened: 1 files or views"), std::string::npos) << turned_out;
  EXPECT_NE(pressed_out.find("opened: 1 files or views"), std::string::npos) << pressed_out;
}

// A vector map opens framed by --frame in its --style: a lens inside that frame is shown, one
// beyond it refused as beyond a 400 x 381 picture.
TEST_F(View, ASourceOpensWithItsFrameAndStyle) {
  const std::string examples = std::string(GEOLENS_SOURCE_DIR) + "/examples/";
  const std::string map = examples + "europe.geojson --style " + examples +
                          "europe_style.json --frame 400x381 --size 320x240 ";
  const ViewRun shown =
      run(map + "--lens circle:150,165,25:3 --screenshot " + path("map.png") + " --frames 1");
  ASSERT_EQ(shown.code, 0) << shown.err;
  // The style's sea, #a9cbe6, at the picture's top left corner: the frame fitted to the window is
  // 252 px wide (240 / 381 of 400), 34 px from its side.
  const Image out = load_image(path("map.png"));
  const uint8_t* sea = out.at(38, 3);
  EXPECT_NEAR(sea[0], 0xa9, 12);
  EXPECT_NEAR(sea[1], 0xcb, 12);
  EXPECT_NEAR(sea[2], 0xe6, 12);
  expect_refused(run(map + "--lens circle:500,300,20 --screenshot " + path("x.png")), 2, "400x381");
}

// Mean squared difference between neighbouring pixels (right and below) of the grey of `image` in
// [x0, x1) x [y0, y1): how sharp it is there.
double gradient_energy(const Image& image, int x0, int y0, int x1, int y1) {
  const auto grey = [&](int x, int y) {
    const uint8_t* p = image.at(x, y);
    return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
  };
  double sum = 0;
  int n = 0;
  for (int y = y0; y + 1 < y1; ++y)
    for (int x = x0; x + 1 < x1; ++x, ++n)
      sum += std::pow(grey(x + 1, y) - grey(x, y), 2) + std::pow(grey(x, y + 1) - grey(x, y), 2);
  return sum / n;
}

// A vector map has detail finer than its frame: once the lens is at rest the viewer shows the
// focus rendered from the finer levels with its labels, as `geolens magnify` draws it, not the
// frame's pixels magnified (which `set detail off` shows).
TEST_F(View, AVectorMapShowsItsDetailInTheFocus) {
  const std::string examples = std::string(GEOLENS_SOURCE_DIR) + "/examples/";
  const std::string map =
      examples + "europe.geojson --style " + examples + "europe_style.json --frame 800x763 ";
  const std::string lens = " --lens circle:295,328,50:4";
  const std::string magnified = path("magnify.png");
  ASSERT_EQ(std::system((std::string(GEOLENS_CLI) + " magnify " + examples + "europe.geojson " +
                         "--style " + examples + "europe_style.json --size 800x763" + lens +
                         " -o " + magnified + " > /dev/null")
                            .c_str()),
            0);
  // The window is the frame's size: one window pixel per frame pixel.
  auto view = [&](const std::string& name, const std::string& lines) {
    std::ofstream(path(name + ".txt"))
        << "set outlines off\n"
        << lines << "screenshot " << path(name + ".png") << "\nquit\n";
    const ViewRun r = run(map + "--size 800x763 --stats --script " + path(name + ".txt") + lens);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    return std::make_pair(load_image(path(name + ".png")), r.out);
  };
  const auto [on, on_stats] = view("on", "");
  const auto [off, off_stats] = view("off", "set detail off\n");
  const Image reference = load_image(magnified);
  ASSERT_EQ(on.width, reference.width);
  ASSERT_EQ(on.height, reference.height);
  EXPECT_NE(on_stats.find("detail: shown, 800 x 763 texels for 800 x 763 window pixels"),
            std::string::npos)
      << on_stats;
  EXPECT_NE(off_stats.find("detail: none shown (not ready or off)"), std::string::npos)
      << off_stats;
  // The focus: the lens's 50 px radius shown 4x, 200 px about (295, 328); a square well within.
  const int x0 = 295 - 120, y0 = 328 - 120, x1 = 295 + 120, y1 = 328 + 120;
  const double on_difference = mean_difference(on, reference, x0, y0, x1, y1);
  const double off_difference = mean_difference(off, reference, x0, y0, x1, y1);
  const double on_energy = gradient_energy(on, x0, y0, x1, y1);
  const double off_energy = gradient_energy(off, x0, y0, x1, y1);
  const double reference_energy = gradient_energy(reference, x0, y0, x1, y1);
  // Measured: 0.00 and 24.25 grey levels; gradient energy 1177 (detail), 206 (frame pixels),
  // 1177 (magnify).
  RecordProperty("focus_difference_detail", std::to_string(on_difference));
  RecordProperty("focus_difference_pixels", std::to_string(off_difference));
  RecordProperty("focus_energy_detail", std::to_string(on_energy));
  RecordProperty("focus_energy_pixels", std::to_string(off_energy));
  EXPECT_LT(on_difference, 2.0);
  EXPECT_LT(on_difference, 0.5 * off_difference);
  EXPECT_GT(on_energy, 1.5 * off_energy);
  EXPECT_NEAR(on_energy / reference_energy, 1.0, 0.2);
  // Beyond the lens's footprint both show the frame.
  EXPECT_LT(mean_difference(on, off, 700, 0, 800, 763), 3.0);
}

// The lenses exported from a view of a vector map carry its frame and style, so `magnify` with
// them frames the map as the viewer did (not at its own default width) and shows what the view
// shows.
TEST_F(View, AnExportedVectorMapViewIsReproducedByMagnify) {
  const std::string examples = std::string(GEOLENS_SOURCE_DIR) + "/examples/";
  std::ofstream(path("export.txt")) << "set outlines off\nscreenshot " << path("view.png")
                                    << "\nexport " << path("lenses.txt") << "\nquit\n";
  const ViewRun r = run(examples + "europe.geojson --style " + examples +
                        "europe_style.json --frame 600x572 --size 600x572 --lens "
                        "circle:220,245,40:3 --script " +
                        path("export.txt"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::string arguments = read_text(path("lenses.txt"));
  arguments = arguments.substr(0, arguments.find('\n'));
  EXPECT_NE(arguments.find("--size 600x572 --style " + examples + "europe_style.json"),
            std::string::npos)
      << arguments;
  ASSERT_EQ(std::system((std::string(GEOLENS_CLI) + " magnify " + examples + "europe.geojson " +
                         arguments + " -o " + path("magnify.png") + " 2> /dev/null")
                            .c_str()),
            0);
  const Image view = load_image(path("view.png")), magnified = load_image(path("magnify.png"));
  ASSERT_EQ(magnified.width, 600);
  ASSERT_EQ(magnified.height, 572);
  EXPECT_LT(mean_difference(view, magnified, 0, 0, 600, 572), 3.0);
  EXPECT_LT(mean_difference(view, magnified, 220 - 90, 245 - 90, 220 + 90, 245 + 90), 3.0);
}

TEST_F(View, ScreenshotAfterFramesWaitsForTheSolver) {
  const ViewRun r = run(path("in.png") + " --size 320x240 --lens circle:160,120,24:2.5 " +
                        "--screenshot " + path("out.png") + " --frames 1");
  ASSERT_EQ(r.code, 0) << r.err;
  const Image out = load_image(path("out.png"));
  // Outlines on: the lens is drawn, and solved (not the identity).
  EXPECT_GT(mean_difference(out, source_, 120, 80, 200, 160), 20.0);
}

TEST_F(View, BadInputEndsWithOneLineAndAnExitCode) {
  const std::string size = " --size 320x240 ";
  expect_refused(run(path("missing.png") + size + "--screenshot " + path("o.png")), 2,
                 "missing.png");
  // The input is never overwritten.
  const auto bytes = fs::file_size(path("in.png"));
  expect_refused(run(path("in.png") + size + "--screenshot " + path("in.png")), 2, "input image");
  expect_refused(run(path("in.png") + size + "--screenshot " + path("o.png") + " --frame-log " +
                     path("in.png")),
                 2, "input image");
  expect_refused(run(path("in.png") + size + "--screenshot " + path("o.png") + " --frame-log " +
                     path("nowhere/f.csv")),
                 2, "does not exist");
  EXPECT_EQ(fs::file_size(path("in.png")), bytes);
  expect_refused(run(path("in.png") + size + "--lens circle:500,1,2 --screenshot " + path("o.png")),
                 2, "circle:500,1,2");
  std::ofstream(path("bad.txt")) << "set outlines off\nframe 3 zoom 1\n";
  expect_refused(run(path("in.png") + " --script " + path("bad.txt")), 2, "bad.txt:2");
  std::ofstream(path("unknown.txt")) << "frame 1 fly 1 2\n";
  expect_refused(run(path("in.png") + " --script " + path("unknown.txt")), 2, "unknown.txt:1");
  std::ofstream(path("nolens.txt")) << "frame 1 move 2 10 10\nquit\n";
  expect_refused(run(path("in.png") + " --script " + path("nolens.txt")), 2, "no lens 2");
  expect_refused(run(path("in.png") + " --script " + path("none.txt")), 2, "none.txt");
  expect_refused(run(path("in.png") + " --method sideways"), 2, "sideways");
  // No display; no OpenGL 3.3 (Mesa made to offer 3.0 only).
  expect_refused(run(path("in.png") + size + "--screenshot " + path("o.png"),
                     "env -u DISPLAY -u WAYLAND_DISPLAY "),
                 3, "DISPLAY");
  expect_refused(run(path("in.png") + size + "--screenshot " + path("o.png"),
                     "MESA_GL_VERSION_OVERRIDE=3.0 " + on_display()),
                 3, "OpenGL 3.3");
  EXPECT_FALSE(fs::exists(path("o.png")));
}

}  // namespace
}  // namespace geolens
