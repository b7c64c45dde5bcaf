#include "script.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

#include "geolens/core/errors.h"
#include "geolens/core/parse.h"
#include "geolens/io/image.h"
#include "geolens/lens/geometric_lens.h"
#include "lens_solver.h"

namespace geolens::view {

namespace fs = std::filesystem;

void check_screenshot_path(const std::string& path, const std::string& input_image,
                           const std::string& what) {
  require(is_writable_image_path(path), what.c_str(),
          "'" + path + "' must end in .png, .jpg or .jpeg");
  const fs::path parent = fs::path(path).parent_path();
  require(parent.empty() || fs::is_directory(parent), what.c_str(),
          "the folder of '" + path + "' does not exist");
  if (input_image.empty()) return;
  std::error_code error;
  const bool same = fs::exists(path) && fs::exists(input_image)
                        ? fs::equivalent(path, input_image, error)
                        : fs::weakly_canonical(path, error) == fs::weakly_canonical(input_image);
  require(!same, what.c_str(), "'" + path + "' is the input image; it is never overwritten");
}

std::string where(const std::string& script, const ScriptEvent& event) {
  return "script " + script + ":" + std::to_string(event.line);
}

namespace {

// Checks a `set NAME VALUE` event's name and value.
void check_set(const std::string& name, const std::string& value) {
  if (name == "mesh") {
    const double m = parse_integer(value, "set mesh");
    if (m < 4 || m > 1000) throw InvalidInput("set mesh: must be in [4, 1000], got " + value);
  } else if (name == "method" || name == "split") {
    if (!is_method_name(value) && !(name == "split" && value == "off"))
      throw InvalidInput("set " + name + ": unknown method '" + value + "' (" + method_list() +
                         (name == "split" ? ", or off)" : ")"));
  } else if (name == "model") {
    parse_lens_model(value);
  } else if (name == "wireframe" || name == "heatmap" || name == "outlines" || name == "panel" ||
             name == "detail") {
    if (value != "on" && value != "off")
      throw InvalidInput("expected on or off, got '" + value + "'");
  } else if (name == "heat_max") {
    if (parse_number(value, "set heat_max") < 0)
      throw InvalidInput("set heat_max: must be >= 0 (0: the largest shown), got " + value);
  } else {
    throw InvalidInput("set: unknown option '" + name +
                       "' (mesh, method, split, model, wireframe, heatmap, heat_max, outlines, "
                       "panel, detail)");
  }
}

// Checks a `press` or `release` event's button and modifiers.
void check_buttons(const std::vector<std::string>& a) {
  if (a[0] != "left" && a[0] != "right")
    throw InvalidInput("expected the button left or right, got '" + a[0] + "'");
  for (size_t i = 1; i < a.size(); ++i)
    if (a[i] != "ctrl" && a[i] != "shift" && a[i] != "double")
      throw InvalidInput("expected the modifier ctrl, shift or double, got '" + a[i] + "'");
}

// A `set NAME VALUE` event (checked by check_set) applied to the viewer.
void apply_set(const std::string& name, const std::string& value, Viewer& viewer) {
  if (name == "mesh") viewer.set_mesh(int(parse_number(value, "set")));
  if (name == "method") viewer.set_method(value);
  if (name == "split") viewer.set_split(value == "off" ? "" : value);
  if (name == "model") viewer.set_model(parse_lens_model(value));
  if (name == "wireframe") viewer.wireframe = value == "on";
  if (name == "heatmap") viewer.heatmap = value == "on";
  if (name == "heat_max") viewer.set_heat_max(parse_number(value, "set"));
  if (name == "outlines") viewer.outlines = value == "on";
  if (name == "panel") viewer.panel = value == "on";
  if (name == "detail") viewer.detail = value == "on";
}

// Checks one event's arguments; throws InvalidInput with what is wrong (the caller adds where).
void check_event(const ScriptEvent& e, const std::string& input_image) {
  const auto& a = e.args;
  auto count = [&](size_t lo, size_t hi, const char* usage) {
    if (a.size() < lo || a.size() > hi)
      throw InvalidInput("'" + e.command + "' takes " + usage + ", got " +
                         std::to_string(a.size()) + " arguments");
  };
  auto lens = [&](size_t i) {
    const double v = parse_integer(a[i], "lens number");
    if (v < 1) throw InvalidInput("lens numbers start at 1, got " + a[i]);
  };
  auto numbers = [&](size_t from, size_t to) {
    for (size_t i = from; i < to; ++i) parse_number(a[i], e.command + " argument " + a[i]);
  };
  const std::string& c = e.command;
  if (c == "move") {
    count(3, 3, "LENS X Y");
    lens(0);
    numbers(1, 3);
  } else if (c == "drag") {
    count(4, 4, "LENS X Y FRAMES");
    lens(0);
    numbers(1, 3);
    if (parse_integer(a[3], "drag frames") < 1)
      throw InvalidInput("drag frames must be >= 1, got " + a[3]);
  } else if (c == "zoom" || c == "radius") {
    count(2, 2, "LENS VALUE");
    lens(0);
    numbers(1, 2);
  } else if (c == "remove" || c == "select") {
    count(1, 1, "LENS");
    lens(0);
  } else if (c == "add") {
    count(1, 1, "a lens spec (circle:X,Y,R[:ZOOM] or polygon:FILE[:ZOOM])");
  } else if (c == "set") {
    count(2, 2, "NAME VALUE");
    check_set(a[0], a[1]);
  } else if (c == "mouse") {
    count(2, 2, "X Y (window pixels)");
    numbers(0, 2);
  } else if (c == "press" || c == "release") {
    count(1, 4, "left|right [ctrl] [shift] [double]");
    check_buttons(a);
  } else if (c == "polygon") {
    if (a.size() < 6 || a.size() % 2 != 0)
      throw InvalidInput("'polygon' takes X Y pairs of at least 3 vertices (window pixels), got " +
                         std::to_string(a.size()) + " numbers");
    numbers(0, a.size());
  } else if (c == "export") {
    count(1, 1, "PATH (.txt)");
    check_export_path(a[0], input_image);
  } else if (c == "scroll") {
    count(1, 2, "DY [shift]");
    numbers(0, 1);
    if (a.size() == 2 && a[1] != "shift")
      throw InvalidInput("expected the modifier shift, got '" + a[1] + "'");
  } else if (c == "key") {
    count(1, 1, "delete|fit|wireframe|heatmap|polygon|escape");
    if (a[0] != "delete" && a[0] != "fit" && a[0] != "wireframe" && a[0] != "heatmap" &&
        a[0] != "polygon" && a[0] != "escape")
      throw InvalidInput("unknown key '" + a[0] +
                         "' (delete, fit, wireframe, heatmap, polygon, escape)");
  } else if (c == "orbit") {
    count(2, 2, "DAZIMUTH DELEVATION (degrees)");
    numbers(0, 2);
  } else if (c == "screenshot") {
    count(1, 2, "PATH [panel]");
    check_screenshot_path(a[0], input_image, "screenshot");
    if (a.size() == 2 && a[1] != "panel")
      throw InvalidInput("expected 'panel' after the path, got '" + a[1] + "'");
  } else if (c == "wait" || c == "quit") {
    count(0, 0, "no arguments");
  } else {
    throw InvalidInput("unknown command '" + c +
                       "' (move, drag, zoom, radius, add, remove, select, set, mouse, press, "
                       "release, scroll, key, orbit, polygon, export, screenshot, wait, quit)");
  }
}

}  // namespace

std::vector<ScriptEvent> parse_script(const std::string& path, const std::string& input_image) {
  std::ifstream in(path);
  require(bool(in), "--script", "cannot read '" + path + "'");
  std::vector<ScriptEvent> events;
  std::string text;
  int line = 0, frame = 0;
  while (std::getline(in, text)) {
    ++line;
    const size_t hash = text.find('#');
    if (hash != std::string::npos) text.resize(hash);
    std::istringstream words(text);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    if (w.empty()) continue;
    ScriptEvent e;
    e.line = line;
    try {
      size_t first = 0;
      if (w[0] == "frame") {
        if (w.size() < 3) throw InvalidInput("expected 'frame N COMMAND ...'");
        const double n = parse_integer(w[1], "frame");
        if (n < frame || n > 1e8)
          throw InvalidInput("frame " + w[1] + " is before the line above's frame " +
                             std::to_string(frame) + " (frames never go back)");
        frame = int(n);
        first = 2;
      }
      e.frame = frame;
      e.command = w[first];
      e.args.assign(w.begin() + long(first) + 1, w.end());
      check_event(e, input_image);
    } catch (const InvalidInput& error) {
      throw InvalidInput(where(path, e) + ": " + error.what());
    }
    events.push_back(std::move(e));
  }
  require(!in.bad(), "--script", "cannot read '" + path + "'");
  return events;
}

ScriptRunner::ScriptRunner(std::string path, std::vector<ScriptEvent> events)
    : path_(std::move(path)), events_(std::move(events)) {}

ScriptActions ScriptRunner::step(int frame, Viewer& viewer) {
  ScriptActions actions;
  for (Drag& d : drags_) {
    ++d.done;
    try {
      viewer.move_lens(d.lens, d.from + (d.to - d.from) * double(d.done) / d.steps, true);
    } catch (const InvalidInput& error) {
      throw InvalidInput(where(path_, d.event) + ": " + error.what());
    }
  }
  std::erase_if(drags_, [](const Drag& d) { return d.done >= d.steps; });
  while (next_ < events_.size() && events_[next_].frame <= frame) {
    const ScriptEvent& e = events_[next_++];
    try {
      apply(e, viewer, actions);
    } catch (const InvalidInput& error) {
      throw InvalidInput(where(path_, e) + ": " + error.what());
    }
  }
  return actions;
}

void ScriptRunner::apply(const ScriptEvent& e, Viewer& viewer, ScriptActions& actions) {
  const auto& a = e.args;
  const std::string& c = e.command;
  auto num = [&](size_t i) { return parse_number(a[i], c); };
  auto lens = [&](size_t i) {
    const size_t index = size_t(parse_integer(a[i], "lens number")) - 1;
    viewer.check_index(index, c);
    return index;
  };
  auto mods = [&](size_t from) {
    Modifiers m;
    for (size_t i = from; i < a.size(); ++i)
      (a[i] == "ctrl" ? m.ctrl : a[i] == "shift" ? m.shift : m.double_click) = true;
    return m;
  };
  if (c == "move") {
    viewer.move_lens(lens(0), {num(1), num(2)}, false);
  } else if (c == "drag") {
    const size_t index = lens(0);
    drags_.push_back(
        Drag{e, index, viewer.lenses()[index].region.peak(), {num(1), num(2)}, int(num(3))});
  } else if (c == "zoom") {
    viewer.set_zoom(lens(0), num(1));
  } else if (c == "radius") {
    viewer.set_radius(lens(0), num(1));
  } else if (c == "remove") {
    viewer.remove_lens(lens(0));
  } else if (c == "select") {
    viewer.select(lens(0));
  } else if (c == "add") {
    viewer.add_lenses(a[0]);
  } else if (c == "set") {
    apply_set(a[0], a[1], viewer);
  } else if (c == "mouse") {
    viewer.mouse_move({num(0), num(1)});
  } else if (c == "press" || c == "release") {
    viewer.mouse_button(a[0] == "left" ? Button::kLeft : Button::kRight, c == "press", mods(1));
  } else if (c == "polygon") {
    // As the mouse draws one: P, a click at each vertex, a double click at the last.
    viewer.start_polygon();
    Modifiers second;
    second.double_click = true;
    for (size_t i = 0; i < a.size(); i += 2) {
      viewer.mouse_move({num(i), num(i + 1)});
      viewer.mouse_button(Button::kLeft, true, {});
      viewer.mouse_button(Button::kLeft, false, {});
    }
    viewer.mouse_button(Button::kLeft, true, second);
    viewer.mouse_button(Button::kLeft, false, {});
    if (viewer.drawing_polygon()) throw InvalidInput("polygon: " + viewer.message);
  } else if (c == "export") {
    viewer.export_lenses(a[0]);
  } else if (c == "scroll") {
    viewer.scroll(num(0), mods(1));
  } else if (c == "key") {
    if (a[0] == "delete") viewer.delete_selected();
    if (a[0] == "fit") viewer.fit_view();
    if (a[0] == "wireframe") viewer.wireframe = !viewer.wireframe;
    if (a[0] == "heatmap") viewer.heatmap = !viewer.heatmap;
    if (a[0] == "polygon") viewer.start_polygon();
    if (a[0] == "escape") viewer.cancel_polygon();
  } else if (c == "orbit") {
    viewer.orbit(num(0), num(1));
  } else if (c == "screenshot") {
    actions.screenshots.push_back({a[0], a.size() == 2});
  } else if (c == "wait") {
    viewer.wait_idle();
  } else if (c == "quit") {
    actions.quit = true;
  }
}

}  // namespace geolens::view
