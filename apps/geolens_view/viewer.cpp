#include "viewer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <utility>

#include "geolens/core/errors.h"
#include "geolens/geometry/roi.h"
#include "geolens/io/file_io.h"
#include "geolens/lens/lens.h"
#include "geolens/lens/lens_spec.h"
#include "geolens/measure/distortion.h"
#include "geolens/render/annotate.h"
#include "geolens/render/render.h"
#include "geolens/render3d/camera.h"
#include "geolens/source/source_file.h"
#include "geolens/warp/warp_map.h"

namespace geolens::view {

namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

// The region moved by `delta` and scaled by `factor` about its peak, source pixels; nullopt
// for a kind that cannot be (a mask blob). Throws InvalidInput for a degenerate result.
std::optional<Region> transformed(const Region& region, const Eigen::Vector2d& delta,
                                  double factor) {
  if (const std::optional<Circle> c = region.circle())
    return Region::circle(c->center + delta, c->radius * factor);
  if (region.kind() != "polygon") return std::nullopt;
  if (factor == 1) return region.translated(delta);  // a drag: its rasters kept, not made again
  const Eigen::Vector2d peak = region.peak();
  std::vector<Eigen::Vector2d> vertices = region.anchors();
  for (Eigen::Vector2d& v : vertices) v = peak + delta + (v - peak) * factor;
  return Region::polygon(vertices);
}

}  // namespace

std::vector<std::array<uint8_t, 3>> heat_colours(const TriangleDistortion& triangles,
                                                 double max_value) {
  require(max_value > 0, "heat_colours", "the maximum must be > 0, got " + number(max_value));
  std::vector<std::array<uint8_t, 3>> colours(size_t(triangles.conformal.size()));
  for (size_t f = 0; f < colours.size(); ++f)
    colours[f] = triangles.flipped(Eigen::Index(f))
                     ? kFlippedColour
                     : heat_colour(triangles.conformal(Eigen::Index(f)) / max_value);
  return colours;
}

Viewer::Viewer(const LensOptions& options, const std::string& method)
    : options_(options), method_(method) {
  validate(options_);
  require(is_method_name(method_), "--method",
          "unknown method '" + method_ + "' (" + method_list() + ")");
}

void Viewer::open(Image image, const std::string& path) {
  require(image.width > 0 && image.height > 0, "Viewer::open", "'" + path + "' is empty");
  image_ = std::move(image);
  image_path_ = path;
  ++image_generation_;
  // A source with detail is set again by show_source.
  detail_worker_.reset();
  detail_asked_.reset();
  detail_.reset();
  // Keep the lenses that still fit.
  std::vector<Lens> kept;
  std::vector<std::string> specs;
  for (size_t i = 0; i < lenses_.size(); ++i) {
    try {
      validate_lens(lenses_[i], image_.width, image_.height);
      kept.push_back(lenses_[i]);
      specs.push_back(specs_[i]);
    } catch (const InvalidInput&) {
    }
  }
  lenses_ = std::move(kept);
  specs_ = std::move(specs);
  selected_.reset();
  dragged_.reset();
  drawn_.reset();
  // Until the first answer, the image as it is.
  show_identity(0);
  show_identity(1);
  restart_solver();
  fit_view();
}

void Viewer::open_file(const std::string& path) {
  show_source(open_frame(path, source_options), std::nullopt);
}

void Viewer::try_open(const std::string& path) {
  if (!opener_) opener_ = std::make_unique<SourceOpener>();
  asked_ = Asked{opener_->submit(path, source_options), path, std::nullopt};
}

bool Viewer::orbit(double d_azimuth, double d_elevation) {
  if (!orbits_ || (asked_ && !asked_->camera)) return false;
  // From the camera asked last: presses made while a view renders add up.
  const auto [from_azimuth, from_elevation] =
      asked_ ? *asked_->camera : std::make_pair(azimuth_, elevation_);
  const double azimuth = std::remainder(from_azimuth + d_azimuth, 360.0);
  const double elevation = std::clamp(from_elevation + d_elevation, -85.0, 85.0);
  SourceFileOptions options = source_options;
  options.view = std::to_string(azimuth) + "," + std::to_string(elevation);
  if (!opener_) opener_ = std::make_unique<SourceOpener>();
  asked_ =
      Asked{opener_->submit(image_path_, options), image_path_, std::make_pair(azimuth, elevation)};
  return true;
}

std::string Viewer::status() const {
  if (!asked_) return "";
  if (!asked_->camera) return "opening " + asked_->path + " ...";
  char view[64];
  std::snprintf(view, sizeof view, "%g,%g", asked_->camera->first, asked_->camera->second);
  return std::string("rendering view ") + view + " ...";
}

bool Viewer::take_opened() {
  if (!asked_) return false;
  std::optional<SourceOpener::Answer> answer = opener_->take();
  // An answer to a request replaced since is dropped: the latest one is on its way.
  if (!answer || answer->request != asked_->request) return false;
  const Asked asked = std::move(*asked_);
  asked_.reset();
  try {
    if (!answer->opened) throw InvalidInput(answer->error);
    show_source(std::move(*answer->opened), asked.camera);
    ++opened_count_;
    opened_ms_ = answer->ms;
    message.clear();
    return true;
  } catch (const std::exception& e) {
    message = e.what();  // the current image is kept
    return false;
  }
}

void Viewer::show_source(OpenedSource opened, std::optional<std::pair<double, double>> camera) {
  const bool orbits = opened.kind == "mesh" || opened.kind == "volume";
  if (orbits && !camera) {
    OrbitCamera view;
    parse_view(source_options.view, view);  // valid: the scene was opened with it
    camera.emplace(view.azimuth_degrees, view.elevation_degrees);
  }
  open(std::move(opened.image), opened.path);
  orbits_ = orbits;
  source_kind_ = opened.kind;
  azimuth_ = camera ? camera->first : 0;
  elevation_ = camera ? camera->second : 0;
  if (opened.detail) detail_worker_ = std::make_unique<DetailWorker>(std::move(opened.detail));
}

void Viewer::add_lenses(const std::string& spec) {
  require(has_image(), "add", "no image is open");
  const std::vector<Lens> parsed =
      parse_lens_spec(spec, 2.0, Profile::kGaussian, 0, image_.width, image_.height);
  const std::optional<LensSpecFile> file = lens_spec_file(spec);
  for (size_t k = 0; k < parsed.size(); ++k) {
    lenses_.push_back(parsed[k]);
    // A mask's blobs come back from the one file: exported once, with the first blob.
    specs_.push_back(file && k == 0 ? file->kind + ":" + file->path : "");
  }
  selected_ = lenses_.size() - 1;
  changed(false);
}

void Viewer::add_lens(const Lens& lens) {
  require(has_image(), "add", "no image is open");
  validate_lens(lens, image_.width, image_.height);
  lenses_.push_back(lens);
  specs_.push_back("");
  selected_ = lenses_.size() - 1;
  changed(false);
}

void Viewer::check_index(size_t index, const std::string& what) const {
  require(index < lenses_.size(), what.c_str(),
          "no lens " + std::to_string(index + 1) + " (there are " + std::to_string(lenses_.size()) +
              ")");
}

void Viewer::remove_lens(size_t index) {
  check_index(index, "remove");
  lenses_.erase(lenses_.begin() + long(index));
  specs_.erase(specs_.begin() + long(index));
  if (dragged_) dragged_.reset();
  selected_.reset();
  changed(false);
}

void Viewer::move_lens(size_t index, const Eigen::Vector2d& peak, bool dragging) {
  check_index(index, "move");
  const Region& region = lenses_[index].region;
  // Kept in the image: the points that define the region (a circle's centre, a polygon's
  // vertices), which validate_lens checks.
  Eigen::AlignedBox2d bounds;
  for (const Eigen::Vector2d& anchor : region.anchors()) bounds.extend(anchor);
  const Eigen::Vector2d lo = -bounds.min(),
                        hi = Eigen::Vector2d(image_.width, image_.height) - bounds.max();
  const Eigen::Vector2d delta = (peak - region.peak()).cwiseMax(lo).cwiseMin(hi);
  replace_region(index, transformed(region, delta, 1.0), "move", "moved");
  changed(dragging);
}

void Viewer::replace_region(size_t index, const std::optional<Region>& region, const char* what,
                            const char* done) {
  Lens& lens = lenses_[index];
  require(region.has_value(), what, "a " + lens.region.kind() + " lens cannot be " + done);
  Lens next = lens;
  next.region = *region;
  validate_lens(next, image_.width, image_.height);
  lens = next;
  // A changed polygon is no longer the file its spec names.
  if (lens.region.kind() == "polygon") specs_[index].clear();
}

void Viewer::set_zoom(size_t index, double zoom) {
  check_index(index, "zoom");
  require(std::isfinite(zoom), "zoom", "zoom must be finite");
  lenses_[index].zoom = std::clamp(zoom, kMinZoom, kMaxZoom);
  changed(false);
}

void Viewer::set_radius(size_t index, double radius) {
  check_index(index, "radius");
  require(std::isfinite(radius) && radius > 0, "radius",
          "radius must be > 0, got " + number(radius));
  const Region& region = lenses_[index].region;
  radius = std::clamp(radius, 2.0, double(std::max(image_.width, image_.height)));
  replace_region(index, transformed(region, Eigen::Vector2d::Zero(), radius / region.size()),
                 "radius", "resized");
  changed(false);
}

std::string Viewer::lens_arguments() const {
  std::string out =
      "--model " + to_string(options_.model) + " --mesh " + std::to_string(options_.mesh);
  // A source framed by its options (a vector map, an SVG, a scene, a tile folder or level list)
  // is framed by magnify the same way only if told the frame and the options: so the lenses,
  // placed in frame pixels, land on the same places.
  if (!source_kind_.empty() && source_kind_ != "image") {
    out += " --size " + std::to_string(image_.width) + "x" + std::to_string(image_.height);
    if (!source_options.style.empty()) out += " --style " + source_options.style;
    if (orbits_) out += " --view " + number(azimuth_) + "," + number(elevation_);
    if (!source_options.transfer.empty()) out += " --transfer " + source_options.transfer;
  }
  std::string notes;
  std::vector<std::string> files;
  for (size_t i = 0; i < lenses_.size(); ++i) {
    const Lens& l = lenses_[i];
    if (const std::optional<Circle> c = l.region.circle()) {
      out += " --lens circle:" + number(c->center.x()) + "," + number(c->center.y()) + "," +
             number(c->radius) + ":" + number(l.zoom);
    } else if (!specs_[i].empty()) {
      if (std::find(files.begin(), files.end(), specs_[i]) != files.end()) continue;
      files.push_back(specs_[i]);
      out += " --lens " + specs_[i] + ":" + number(l.zoom);
    } else if (l.region.kind() == "polygon") {
      notes += "  # lens " + std::to_string(i + 1) + ": a polygon without a file (export it)";
    }
  }
  return out + notes;
}

void check_export_path(const std::string& path, const std::string& input_image) {
  const std::filesystem::path file(path);
  require(file.extension() == ".txt", "export", "'" + path + "' must end in .txt");
  require(file.parent_path().empty() || std::filesystem::is_directory(file.parent_path()), "export",
          "the folder of '" + path + "' does not exist");
  require(input_image.empty() || !same_file(path, input_image), "export",
          "'" + path + "' is the input image; it is never overwritten");
}

std::string Viewer::export_lenses(const std::string& path) {
  check_export_path(path, image_path_);
  const std::filesystem::path file(path);
  const std::string stem = (file.parent_path() / file.stem()).string();
  for (size_t i = 0; i < lenses_.size(); ++i) {
    if (lenses_[i].region.kind() != "polygon" || !specs_[i].empty()) continue;
    const std::string polygon = stem + "-lens-" + std::to_string(i + 1) + ".txt";
    check_export_path(polygon, image_path_);
    std::string text;
    for (const Eigen::Vector2d& v : lenses_[i].region.anchors())
      text += number(v.x()) + " " + number(v.y()) + "\n";
    write_file(polygon, text);
    specs_[i] = "polygon:" + polygon;
  }
  const std::string arguments = lens_arguments();
  write_file(path, arguments + "\n");
  return arguments;
}

void Viewer::start_polygon() {
  if (!has_image()) return;
  drawn_.emplace();
  selected_.reset();
  dragged_.reset();
}

size_t Viewer::polygon_vertices() const { return drawn_ ? drawn_->size() : 0; }

std::vector<Eigen::Vector2d> Viewer::polygon_outline() {
  std::vector<Eigen::Vector2d> outline;
  if (!drawn_) return outline;
  const WarpMap* map = warp_map();
  for (const Eigen::Vector2d& p : *drawn_)
    outline.push_back(origin() + (map ? map->forward(p).value_or(p) : p) * scale());
  outline.push_back(mouse_);
  return outline;
}

std::vector<Viewer::Outline> Viewer::region_outlines(int pane) {
  std::vector<Outline> outlines;
  const SolvedFrame& frame = pane == 0 ? frame_ : split_.frame;
  const WarpMap* map = warp_map(pane);
  if (!map) return outlines;
  const Eigen::Vector2d at = origin() + pane * pane_offset();
  constexpr double kPiece = 2;  // source pixels
  for (size_t k = 0; k < frame.lenses.size(); ++k) {
    const std::optional<std::vector<Eigen::Vector2d>> polygon = frame.lenses[k].region.outline();
    if (!polygon) continue;
    Outline outline;
    // The frame's lenses are the viewer's while their count is (as the renderer's selection).
    outline.selected = selected_ == k && frame.lenses.size() == lenses_.size();
    for (size_t i = 0; i < polygon->size(); ++i) {
      const Eigen::Vector2d a = (*polygon)[i], b = (*polygon)[(i + 1) % polygon->size()];
      const int pieces = std::max(1, int(std::ceil((b - a).norm() / kPiece)));
      for (int j = 0; j < pieces; ++j) {
        const Eigen::Vector2d p = a + (b - a) * (double(j) / pieces);
        outline.points.push_back(at + map->forward(p).value_or(p) * scale());
      }
    }
    outlines.push_back(std::move(outline));
  }
  return outlines;
}

void Viewer::polygon_click(bool double_click) {
  if (!double_click) {
    // A vertex on the last one (the first click of a double click there) is not repeated.
    const std::optional<Eigen::Vector2d> p = source_at(mouse_);
    if (p && (drawn_->empty() || (drawn_->back() - *p).norm() * scale() >= 1))
      drawn_->push_back(*p);
    return;
  }
  try {
    add_lens(Lens{Region::polygon(*drawn_), 2.0});
    drawn_.reset();
  } catch (const InvalidInput& e) {
    message = e.what();  // the drawing stays, to be finished or cancelled (Escape)
  }
}

void Viewer::set_method(const std::string& method) {
  require(is_method_name(method), "set method",
          "unknown method '" + method + "' (" + method_list() + ")");
  if (method == method_) return;
  method_ = method;
  restart_solver();
  show_identity(0);  // not the last method's picture under this one's name
}

void Viewer::show_identity(int pane) {
  if (!has_image()) return;
  auto identity = std::make_shared<Magnification>();
  identity->warp = identity_warp(image_.width, image_.height);
  SolvedFrame& frame = pane == 0 ? frame_ : split_.frame;
  frame = SolvedFrame();
  frame.result = std::move(identity);
  if (pane == 0) {
    accepted_request_ = 0;
    ++frame_generation_;
    measures_ = measure_frame(frame_);
  } else {
    ++split_.generation;
    split_.measures = measure_frame(split_.frame);
  }
}

std::string Viewer::pane_state(int pane) const {
  if (pane == 1 && split_.failed) return "failed";
  const bool waiting = pane == 0 ? solver_ && accepted_request_ != submitted_request_
                                 : split_.solver && split_.frame.request != split_.submitted;
  return waiting ? "waiting" : "";
}

void Viewer::set_mesh(int mesh) {
  LensOptions next = options_;
  next.mesh = mesh;
  validate(next);
  if (next.mesh == options_.mesh) return;
  options_ = next;
  restart_solver();
}

void Viewer::set_model(LensModel model) {
  if (model == options_.model) return;
  options_.model = model;
  restart_solver();
}

void Viewer::set_split(const std::string& method) {
  require(method.empty() || is_method_name(method), "split",
          "unknown method '" + method + "' (" + method_list() + ")");
  if (method == split_.method) return;
  split_.method = method;
  restart_solver();
  if (!method.empty()) show_identity(1);  // not the last method's picture under this one's name
}

void Viewer::restart_solver() {
  if (!has_image()) return;
  solver_.reset();  // cancels the solve under way before the next starts
  solver_ = std::make_unique<LensSolver>(image_.width, image_.height, method_, options_);
  split_.solver.reset();
  split_.frame.request = split_.submitted = 0;  // the new solver numbers its requests from 1
  if (!split_.method.empty())
    split_.solver =
        std::make_unique<LensSolver>(image_.width, image_.height, split_.method, options_);
  accepted_request_ = 0;
  requested_at_.clear();
  changed(false);
}

void Viewer::changed(bool dragging) {
  dirty_ = true;
  if (!dragging) drop_stale_ = true;
}

double Viewer::heat_max() const {
  if (heat_max_ > 0) return heat_max_;
  double largest = measures_.conformal_max;
  if (!split_.method.empty()) largest = std::max(largest, split_.measures.conformal_max);
  return largest > 0 ? largest : 1;  // 0: the identity
}

void Viewer::set_heat_max(double value) {
  require(std::isfinite(value) && value >= 0, "heat max",
          "must be >= 0 (0: the largest shown), got " + number(value));
  heat_max_ = value;
}

void Viewer::set_window(int width, int height) {
  window_width_ = std::max(width, 1);
  window_height_ = std::max(height, 1);
}

double Viewer::scale() const {
  if (!has_image()) return 1;
  return view_zoom_ *
         std::min(double(pane_width()) / image_.width, double(window_height_) / image_.height);
}

Eigen::Vector2d Viewer::origin() const {
  const Eigen::Vector2d window(pane_width(), window_height_);
  const Eigen::Vector2d size(image_.width, image_.height);
  return (window - size * scale()) / 2 + pan_;
}

void Viewer::fit_view() {
  view_zoom_ = 1;
  pan_.setZero();
}

const WarpMap* Viewer::warp_map(int pane) {
  const SolvedFrame& frame = pane == 0 ? frame_ : split_.frame;
  std::optional<WarpMap>& map = pane == 0 ? map_ : split_.map;
  std::uint64_t& generation = pane == 0 ? map_generation_ : split_.map_generation;
  const std::uint64_t latest = pane == 0 ? frame_generation_ : split_.generation;
  if (!frame.result) return nullptr;
  if (!map || generation != latest) {
    map.emplace(frame.result->warp);
    generation = latest;
  }
  return &*map;
}

std::pair<int, Eigen::Vector2d> Viewer::pane_at(const Eigen::Vector2d& at) const {
  if (split_.method.empty() || at.x() < pane_width()) return {0, at};
  return {1, at - pane_offset()};
}

std::optional<Eigen::Vector2d> Viewer::source_at(const Eigen::Vector2d& at) {
  const auto [pane, local] = pane_at(at);
  const WarpMap* map = warp_map(pane);
  return map ? map->inverse((local - origin()) / scale()) : std::nullopt;
}

std::optional<size_t> Viewer::lens_at(const Eigen::Vector2d& at) {
  const std::optional<Eigen::Vector2d> p = source_at(at);
  if (!p) return std::nullopt;
  std::optional<size_t> best;
  for (size_t i = 0; i < lenses_.size(); ++i)
    if (lenses_[i].region.distance(*p) <= 0 &&
        (!best || lenses_[i].region.size() < lenses_[*best].region.size()))
      best = i;
  return best;
}

void Viewer::mouse_move(const Eigen::Vector2d& at) {
  const Eigen::Vector2d delta = at - mouse_;
  mouse_ = at;
  if (dragged_) {
    try {
      move_lens(*dragged_, drag_peak_ + (at - drag_from_) / scale(), true);
    } catch (const InvalidInput& e) {
      message = e.what();
      dragged_.reset();
    }
  }
  if (panning_) pan_ += delta;
}

void Viewer::mouse_button(Button button, bool pressed, Modifiers mods) {
  if (!has_image()) return;
  if (button == Button::kRight) {
    panning_ = pressed;
    return;
  }
  if (!pressed) {
    dragged_.reset();
    return;
  }
  if (drawn_) {
    polygon_click(mods.double_click);
    return;
  }
  if (mods.ctrl) {
    // A circle lens at the source point shown under the pointer.
    const std::optional<Eigen::Vector2d> p = source_at(mouse_);
    if (!p) return;
    const double radius = std::max(8.0, 0.08 * std::min(image_.width, image_.height));
    try {
      add_lens(Lens{Region::circle(*p, radius), 2.0});
    } catch (const InvalidInput& e) {
      message = e.what();
    }
    return;
  }
  selected_ = lens_at(mouse_);
  if (selected_) {
    dragged_ = selected_;
    drag_from_ = mouse_;
    drag_peak_ = lenses_[*selected_].region.peak();
  }
}

void Viewer::scroll(double dy, Modifiers mods) {
  if (!has_image() || dy == 0) return;
  if (const std::optional<size_t> lens = lens_at(mouse_)) {
    selected_ = lens;
    try {
      if (mods.shift)
        set_radius(*lens, lenses_[*lens].region.size() * std::pow(1.1, dy));
      else
        set_zoom(*lens, lenses_[*lens].zoom + 0.25 * dy);
    } catch (const InvalidInput& e) {
      message = e.what();
    }
    return;
  }
  // Zoom the whole view about the pointer: the source point under it stays there.
  const Eigen::Vector2d pointer = pane_at(mouse_).second;
  const Eigen::Vector2d under = (pointer - origin()) / scale();
  view_zoom_ = std::clamp(view_zoom_ * std::pow(1.15, dy), 0.1, 64.0);
  pan_.setZero();
  pan_ = pointer - under * scale() - origin();
}

void Viewer::delete_selected() {
  if (selected_) remove_lens(*selected_);
}

bool Viewer::update() {
  const bool opened = take_opened();
  if (!solver_) return opened;
  const auto now = std::chrono::steady_clock::now();
  if (dirty_) {
    submitted_request_ = solver_->submit(lenses_, drop_stale_);
    requested_at_.emplace_back(submitted_request_, now);
    if (split_.solver) split_.submitted = split_.solver->submit(lenses_, drop_stale_);
    dirty_ = drop_stale_ = false;
    // A draft takes a millisecond or two: shown in this frame, not the next (a move took two
    // frames to show under llvmpipe, 29 ms); a slower solve is shown when it is done.
    solver_->wait_for_last(kShowWait);
  }
  if (split_.solver) {
    SolvedFrame f = split_.solver->latest();
    // A request the split's method refuses (classic lenses whose disks overlap) leaves the image
    // as it is in its pane, not the picture of the lenses before.
    const bool failed = !f.error.empty();
    if (failed) message = f.error;
    if (failed && !split_.failed) show_identity(1);
    split_.failed = failed;
    if (!failed && f.request != 0 &&
        (f.request != split_.frame.request || f.result != split_.frame.result)) {
      split_.frame = std::move(f);
      ++split_.generation;
      split_.measures = measure_frame(split_.frame);
    }
  }
  SolvedFrame f = solver_->latest();
  if (!f.error.empty()) message = f.error;
  // A new request answered, or the full frame of the one shown as a draft.
  const bool fresh =
      f.request != 0 && (f.request != accepted_request_ || f.result != frame_.result);
  if (fresh) {
    if (f.error.empty()) message.clear();  // a solve succeeded: what failed before is past
    if (f.request != accepted_request_) {
      frame_requested_at_ = now;
      for (const auto& [request, at] : requested_at_)
        if (request == f.request) frame_requested_at_ = at;
      std::erase_if(requested_at_, [&](const auto& r) { return r.first <= f.request; });
    }
    accepted_request_ = f.request;
    frame_ = std::move(f);
    ++frame_generation_;
    measures_ = measure_frame(frame_);
  }
  update_detail();
  return fresh || opened;
}

std::optional<DetailView> Viewer::detail_view() const {
  if (!detail || !detail_worker_ || !frame_.result || frame_.result->draft || dirty_ ||
      frame_.request != submitted_request_)
    return std::nullopt;
  // The window pixels of pane 0 whose centres are in the frame.
  const double s = scale();
  const Eigen::Vector2d lo = origin(), hi = lo + Eigen::Vector2d(image_.width, image_.height) * s;
  const auto pixel = [](double v) { return int(std::ceil(std::clamp(v - 0.5, -1e6, 1e6))); };
  DetailView view;
  view.frame = frame_generation_;
  view.origin = lo;
  view.scale = s;
  view.x = std::max(pixel(lo.x()), 0);
  view.y = std::max(pixel(lo.y()), 0);
  view.width = std::min(pixel(hi.x()), pane_width()) - view.x;
  view.height = std::min(pixel(hi.y()), window_height_) - view.y;
  if (view.width <= 0 || view.height <= 0) return std::nullopt;
  return view;
}

void Viewer::update_detail() {
  if (!detail_worker_) return;
  // Not while the view is panned: each step of a pan would ask for a picture.
  const std::optional<DetailView> view = detail_view();
  if (view && view != detail_asked_ && !panning_) {
    detail_worker_->submit(frame_.result, *view);
    detail_asked_ = view;
  }
  if (std::shared_ptr<const DetailPicture> latest = detail_worker_->latest(); latest != detail_) {
    detail_ = std::move(latest);
    ++detail_generation_;
  }
  if (const std::string error = detail_worker_->error(); !error.empty()) message = error;
}

const DetailPicture* Viewer::detail_picture() const {
  if (!detail_) return nullptr;
  const std::optional<DetailView> view = detail_view();
  return view && *view == detail_->view ? detail_.get() : nullptr;
}

void Viewer::wait_idle() {
  if (asked_) opener_->wait_idle();  // its answer is shown by the update below
  if (!solver_) {
    update();
    return;
  }
  update();  // submits what changed
  solver_->wait_idle();
  if (split_.solver) split_.solver->wait_idle();
  update();  // asks for the detail of the answer
  if (detail_worker_) {
    detail_worker_->wait_idle();
    update();
  }
}

FrameMeasures measure_frame(const SolvedFrame& frame) {
  FrameMeasures m;
  if (!frame.result) return m;
  const WarpMesh& warp = frame.result->warp;
  m.triangles = measure_triangles(warp);
  const TriangleDistortion& d = m.triangles;
  const DistortionSummary s = summarize(d);
  m.flipped = s.flipped;
  m.conformal_mean = s.conformal_mean;
  m.conformal_max = s.conformal_max;
  m.zoom_measured = frame.result->zoom_measured;
  const std::vector<Lens>& lenses = frame.lenses;
  m.flips.assign(lenses.size(), 0);
  if (lenses.empty()) return m;
  for (Eigen::Index f = 0; f < d.flipped.size(); ++f) {
    if (!d.flipped(f)) continue;
    const Eigen::Vector2d c = (warp.source.row(warp.F(f, 0)) + warp.source.row(warp.F(f, 1)) +
                               warp.source.row(warp.F(f, 2)))
                                  .transpose() /
                              3;
    size_t nearest = 0;
    double best = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < lenses.size(); ++k)
      if (const double dist = lenses[k].region.distance(c); dist < best) {
        best = dist;
        nearest = k;
      }
    ++m.flips[nearest];
  }
  return m;
}

}  // namespace geolens::view
