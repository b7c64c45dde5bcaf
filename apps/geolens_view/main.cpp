// geolens-view: drag geometric (or classic) lenses across an image, solved on a worker thread
// and drawn on the GPU; or, with --script / --screenshot, the same headless for tests and
// pictures.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/core/parse.h"
#include "geolens/io/file_io.h"
#include "geolens/io/image.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens_options.h"
#include "panel.h"
#include "script.h"
#include "viewer.h"
#include "warp_renderer.h"
#include "window.h"

using namespace geolens;
using namespace geolens::view;

namespace {

struct Args {
  std::string image, method = "geometric", split, script, screenshot, size;
  std::string frame, style, view, transfer;  // how a source file is opened
  std::string frame_log;
  std::vector<std::string> lenses;
  std::map<std::string, std::string> options;  // the lens options bound (model, mesh), as given
  int frames = 2;
  bool stats = false, redraw = false;
};

// The window events, handed to the viewer (keys that are the frame loop's own go there too).
class Input final : public WindowInput {
 public:
  explicit Input(Viewer& viewer) : viewer_(viewer) {}
  void mouse_move(const Eigen::Vector2d& at) override { viewer_.mouse_move(at); }
  void mouse_button(Button button, bool pressed, Modifiers mods) override {
    viewer_.mouse_button(button, pressed, mods);
  }
  void scroll(double dy, Modifiers mods) override { viewer_.scroll(dy, mods); }
  void key(Key key) override {
    if (key == Key::kDelete) viewer_.delete_selected();
    if (key == Key::kFit) viewer_.fit_view();
    if (key == Key::kWireframe) viewer_.wireframe = !viewer_.wireframe;
    if (key == Key::kHeatmap) viewer_.heatmap = !viewer_.heatmap;
    if (key == Key::kPolygon) viewer_.start_polygon();
    if (key == Key::kEscape) viewer_.cancel_polygon();
    // The arrow keys orbit a 3D source's camera by 15 degrees (the view is rendered again).
    constexpr double kStep = 15;
    if (key == Key::kLeft) viewer_.orbit(-kStep, 0);
    if (key == Key::kRight) viewer_.orbit(kStep, 0);
    if (key == Key::kUp) viewer_.orbit(0, kStep);
    if (key == Key::kDown) viewer_.orbit(0, -kStep);
  }
  void drop(const std::string& path) override { viewer_.try_open(path); }

 private:
  Viewer& viewer_;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5))];
}

// Everything checked before a window opens.
void check_arguments(const Args& a) {
  require(a.screenshot.empty() || !a.image.empty(), "--screenshot", "needs an IMAGE");
  require(a.script.empty() || !a.image.empty(), "--script", "needs an IMAGE");
  require(a.frames >= 1, "--frames", "must be >= 1, got " + std::to_string(a.frames));
  if (!a.screenshot.empty()) check_screenshot_path(a.screenshot, a.image, "--screenshot");
  if (!a.frame_log.empty()) {
    const std::filesystem::path parent = std::filesystem::path(a.frame_log).parent_path();
    require(parent.empty() || std::filesystem::is_directory(parent), "--frame-log",
            "the folder of '" + a.frame_log + "' does not exist");
    require(a.image.empty() || !same_file(a.frame_log, a.image), "--frame-log",
            "'" + a.frame_log + "' is the input image; it is never overwritten");
  }
}

// The lens options given (--model, --mesh), in the command line's words when wrong.
LensOptions lens_options(const Args& a) {
  LensOptions options;
  try {
    for (const auto& [name, text] : a.options) lens_option_field(name).set(options, text);
  } catch (const InvalidOption& e) {  // in the command line's words
    throw InvalidInput(option_flag(e.option) + ": " + e.problem);
  }
  return options;
}

// The viewer's source options, file and lenses as the arguments give them.
void open(Viewer& viewer, const Args& a) {
  SourceFileOptions source;
  if (!a.frame.empty())
    std::tie(source.width, source.height) = parse_size(a.frame, "--frame", 1, 16384);
  source.style = a.style;
  source.view = a.view;
  source.transfer = a.transfer;
  viewer.source_options = source;
  viewer.set_split(a.split);
  if (!a.image.empty()) viewer.open_file(a.image);
  for (const std::string& spec : a.lenses) {
    require(viewer.has_image(), "--lens", "needs an IMAGE");
    try {
      viewer.add_lenses(spec);
    } catch (const InvalidInput& e) {
      throw InvalidInput("--lens " + spec + ": " + e.what());
    }
  }
  viewer.select(std::nullopt);
}

// What the GPU holds per pane: the frame's generation, the frame and scale of its heatmap (0:
// none), and the viewer's detail picture (its generation; pane 0 only).
struct Shown {
  std::uint64_t frame = 0, heat_frame = 0, detail = 0;
  double heat_max = 0;
};

// The frames' timings --stats prints, milliseconds.
struct FrameTimes {
  std::vector<double> frame_ms, latency_ms, solve_ms;
  int frames_while_opening = 0;  // frames drawn while a file opened or a view rendered
};

// Pane `pane` of the frame: its warp, heat map and detail sent to the GPU where they changed
// since `on_gpu`, then drawn.
void draw_pane(int pane, Viewer& viewer, const Window& window, WarpRenderer& renderer,
               Shown& on_gpu) {
  const SolvedFrame& solved = pane == 0 ? viewer.frame() : viewer.split_frame();
  if (!solved.result) return;  // no image yet
  const FrameMeasures& measures = pane == 0 ? viewer.measures() : viewer.split_measures();
  const std::uint64_t generation =
      pane == 0 ? viewer.frame_generation() : viewer.split_generation();
  if (on_gpu.frame != generation) {
    renderer.set_mesh(pane, solved.result->warp);
    on_gpu.frame = generation;
  }
  if (viewer.heatmap &&
      (on_gpu.heat_frame != on_gpu.frame || on_gpu.heat_max != viewer.heat_max())) {
    renderer.set_heat(pane, solved.result->warp,
                      heat_colours(measures.triangles, viewer.heat_max()));
    on_gpu.heat_frame = on_gpu.frame;
    on_gpu.heat_max = viewer.heat_max();
  }
  // The frame's detail, where the source has some and it is rendered for this view.
  const DetailPicture* detail = pane == 0 ? viewer.detail_picture() : nullptr;
  if (detail && on_gpu.detail != viewer.detail_generation()) {
    renderer.set_detail(detail->image,
                        {detail->view.x, detail->view.y, detail->view.width, detail->view.height});
    on_gpu.detail = viewer.detail_generation();
  }
  DrawSettings settings;
  settings.detail = detail != nullptr;
  settings.window_width = window.framebuffer_width();
  settings.window_height = window.framebuffer_height();
  settings.pane = pane;
  settings.clip_x = pane * viewer.pane_width();
  settings.clip_width = viewer.pane_width();
  settings.origin = viewer.origin() + pane * viewer.pane_offset();
  settings.scale = viewer.has_image() ? viewer.scale() : 0;
  settings.wireframe = viewer.wireframe;
  settings.heatmap = viewer.heatmap;
  if (viewer.outlines)
    for (const Lens& lens : solved.lenses)
      if (const std::optional<Circle> c = lens.region.circle())
        settings.outlines.emplace_back(c->center.x(), c->center.y(), c->radius);
  if (viewer.selected() && solved.lenses.size() == viewer.lenses().size())
    settings.selected = int(*viewer.selected());
  renderer.draw(settings);
}

// What --stats prints at exit.
void print_stats(const FrameTimes& times, const Viewer& viewer, const Window& window,
                 const WarpRenderer& renderer) {
  std::printf(
      "frames %zu: frame time median %.1f ms, p95 %.1f ms; move to shown (%zu frames shown) "
      "median %.1f ms, p95 %.1f ms; solves shown median %.1f ms; solve (last) %.1f ms; %s\n",
      times.frame_ms.size() + 1, percentile(times.frame_ms, 0.5), percentile(times.frame_ms, 0.95),
      times.latency_ms.size(), percentile(times.latency_ms, 0.5),
      percentile(times.latency_ms, 0.95), percentile(times.solve_ms, 0.5), viewer.frame().solve_ms,
      window.gl_description().c_str());
  if (const std::optional<StageTimings>& t = viewer.frame().stages)
    std::printf(
        "stages of the last solve (calibration solves: %d): lift %.2f ms, texture %.2f ms, "
        "factorize %.2f ms, iterate %.2f ms, total %.2f ms\n",
        viewer.frame().solves, t->lift, t->texture, t->factorize, t->iterate, t->total);
  else
    std::printf("stages: none (%s)\n", viewer.method().c_str());
  std::printf("texture: level %d of the image, %d x %d texels\n", renderer.texture_level(),
              renderer.texture_width(), renderer.texture_height());
  if (const DetailPicture* d = viewer.detail_picture())
    std::printf("detail: shown, %d x %d texels for %d x %d window pixels, rendered in %.1f ms\n",
                d->image.width, d->image.height, d->view.width, d->view.height, d->render_ms);
  else
    std::printf("detail: none shown (%s)\n",
                viewer.has_detail() ? "not ready or off" : "the source has none");
  std::printf(
      "opened: %d files or views opened and rendered off the UI thread, the last in %.1f ms; "
      "%d frames drawn meanwhile; longest frame %.1f ms\n",
      viewer.opened_count(), viewer.opened_ms(), times.frames_while_opening,
      times.frame_ms.empty() ? 0.0
                             : *std::max_element(times.frame_ms.begin(), times.frame_ms.end()));
  const CacheCounts& counts = renderer.cache_counts();
  std::printf(
      "picture: %d of %d triangles drawn as triangles (the rest as one quad); pictures drawn "
      "whole %d, in part %d, reused %d\n",
      renderer.moved_triangles(0), renderer.triangles(0), counts.full, counts.partial,
      counts.reused);
}

// A --frame-log row per lens of a frame that shows a new solve: where it is, the zoom asked and
// the zoom it was solved at.
void log_frame(int frame, const SolvedFrame& solved, std::string& log) {
  for (size_t k = 0; k < solved.lenses.size(); ++k) {
    const Eigen::Vector2d p = solved.lenses[k].region.peak();
    char row[160];
    std::snprintf(row, sizeof row, "%d,%zu,%.17g,%.17g,%.17g,%.17g,%d\n", frame, k + 1, p.x(),
                  p.y(), solved.lenses[k].zoom, solved.result->zoom_parameter.at(k),
                  int(solved.result->draft));
    log += row;
  }
}

// The picture the panel asked for, saved; the panel's message says where, or why not.
void save_panel_shot(const std::string& path, const Window& window, Viewer& viewer) {
  try {
    save_image(path, window.read_back_buffer());
    viewer.message = "saved " + path;
  } catch (const std::exception& e) {
    viewer.message = e.what();
  }
}

int run(const Args& a) {
  using Clock = std::chrono::steady_clock;
  check_arguments(a);
  const auto [width, height] =
      a.size.empty() ? std::pair{1280, 800} : parse_size(a.size, "--size", 64, 8192);
  Viewer viewer(lens_options(a), a.method);
  open(viewer, a);
  ScriptRunner script;
  if (!a.script.empty()) script = ScriptRunner(a.script, parse_script(a.script, a.image));

  const bool headless = script.active() || !a.screenshot.empty();
  Window window(width, height, "geolens-view", !headless);
  WarpRenderer renderer;
  renderer.set_caching(!a.redraw);
  Input input(viewer);
  window.set_input(&input);
  PanelState panel;
  std::optional<std::string> panel_shot;  // asked in the panel: taken at the next frame
  std::uint64_t shown_image = 0;
  std::array<Shown, WarpRenderer::kPanes> shown;
  FrameTimes times;
  // --frame-log: per frame that shows a new solve, per lens where it is, the zoom asked and the
  // zoom it was solved at (written at exit).
  std::string frame_log = "frame,lens,x,y,zoom_asked,zoom_got,draft\n";
  auto last = Clock::now();
  for (int frame = 0;; ++frame) {
    window.poll();
    if (window.should_close()) break;
    viewer.set_window(window.framebuffer_width(), window.framebuffer_height());
    const ScriptActions actions = script.step(frame, viewer);
    const bool final = !a.screenshot.empty() && frame + 1 >= a.frames;
    // A picture taken is the answer to every request made: deterministic.
    if (!actions.screenshots.empty() || final || panel_shot)
      viewer.wait_idle();
    else
      viewer.update();
    // A frame drawn while a file opens or a view renders off the UI thread (the image before).
    if (!viewer.status().empty()) ++times.frames_while_opening;
    const bool fresh = viewer.frame_generation() != shown[0].frame;
    if (viewer.image_generation() != shown_image) {
      renderer.set_image(viewer.image());
      shown_image = viewer.image_generation();
    }
    const int panes = viewer.split().empty() ? 1 : 2;
    renderer.clear(window.framebuffer_width(), window.framebuffer_height());
    for (int pane = 0; pane < panes; ++pane)
      draw_pane(pane, viewer, window, renderer, shown[size_t(pane)]);
    // Pictures of the view alone, then of the view with the panel.
    for (const ScriptActions::Shot& shot : actions.screenshots)
      if (!shot.panel) save_image(shot.path, window.read_back_buffer());
    if (final) save_image(a.screenshot, window.read_back_buffer());
    if (panel_shot) save_panel_shot(*panel_shot, window, viewer);
    panel_shot.reset();
    window.begin_ui();
    draw_overlays(viewer);
    if (viewer.panel) panel_shot = draw_panel(viewer, panel).screenshot;
    window.end_ui();
    for (const ScriptActions::Shot& shot : actions.screenshots)
      if (shot.panel) save_image(shot.path, window.read_back_buffer());
    window.swap();
    const auto now = Clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last).count();
    last = now;
    panel.frame_ms = panel.frame_ms == 0 ? ms : 0.9 * panel.frame_ms + 0.1 * ms;
    if (frame > 0) times.frame_ms.push_back(ms);
    if (fresh && frame > 0) {
      times.latency_ms.push_back(
          std::chrono::duration<double, std::milli>(now - viewer.frame_requested_at()).count());
      times.solve_ms.push_back(viewer.frame().solve_ms);
    }
    if (!a.frame_log.empty() && fresh && viewer.frame().result)
      log_frame(frame, viewer.frame(), frame_log);
    if (actions.quit || final) break;
  }
  if (!a.frame_log.empty()) write_file(a.frame_log, frame_log);
  if (a.stats) print_stats(times, viewer, window, renderer);
  return 0;
}

// One line, whatever the message holds.
std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"geolens-view: drag geometric focus+context lenses across an image"};
  app.set_version_flag("--version", std::string("geolens-view ") + GEOLENS_VERSION);
  Args a;
  app.add_option("image", a.image,
                 "image (PNG or JPEG) or source file (a tile folder, .levels, .svg, .geojson, "
                 ".obj, .ply, .nii, .nii.gz, .nrrd) to show");
  app.add_option("--frame", a.frame,
                 "frame WxH of a source without pixels of its own (SVG, vector map, 3D) or the "
                 "pyramid level nearest it (default: the source's own)");
  app.add_option("--style", a.style, "style file (JSON) of a vector map");
  app.add_option("--view", a.view, "camera of a mesh or a volume: AZ,EL in degrees");
  app.add_option("--transfer", a.transfer, "transfer function of a volume: ct, mri or a file");
  app.add_option("--lens", a.lenses,
                 "circle:CX,CY,R[:ZOOM] (source pixels), polygon:FILE[:ZOOM] or "
                 "mask:FILE[:ZOOM]; repeatable");
  app.add_option("--method", a.method, "geometric, or a classic lens: " + method_list())
      ->capture_default_str();
  app.add_option("--split", a.split,
                 "show another method on the right half of the window, on the same lenses");
  for (const char* name : {"model", "mesh"}) {
    const LensOptionField& field = lens_option_field(name);
    std::string& value = a.options[name] = field.get(LensOptions{});
    app.add_option(option_flag(name), value, field.help)
        ->type_name(field.type == LensOptionField::Type::kInteger  ? "INT"
                    : field.type == LensOptionField::Type::kNumber ? "FLOAT"
                                                                   : "TEXT")
        ->capture_default_str();
  }
  app.add_option("--script", a.script, "play timed events from FILE (see the README)");
  app.add_option("--screenshot", a.screenshot,
                 "draw --frames frames, wait for the solver, save the view to OUT.png and exit");
  app.add_option("--frames", a.frames, "frames drawn before --screenshot")->capture_default_str();
  app.add_option("--size", a.size, "window size WxH, pixels (default 1280x800)");
  app.add_option("--frame-log", a.frame_log,
                 "write FILE.csv: per frame that shows a new solve, per lens its place, the zoom "
                 "asked and the zoom got");
  app.add_flag("--stats", a.stats,
               "print frame time and move-to-shown latency (median, p95) at exit");
  app.add_flag("--redraw", a.redraw,
               "draw the picture afresh every frame instead of from its cached copy (a measure "
               "of the drawing's cost)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "geolens-view: error: " << one_line(e.what()) << " (see geolens-view --help)\n";
    return 2;
  }
  try {
    return run(a);
  } catch (const InvalidInput& e) {
    std::cerr << "geolens-view: error: " << one_line(e.what()) << '\n';
    return 2;
  } catch (const WindowError& e) {
    std::cerr << "geolens-view: error: " << one_line(e.what()) << '\n';
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "geolens-view: failed: " << one_line(e.what()) << '\n';
    return 1;
  }
}
