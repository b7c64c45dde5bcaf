#pragma once
// The viewer's state and what the user does to it: the image, the lenses, the view of the
// whole picture (pan and zoom), the selection, and the mouse and keys that change them. Holds
// no GL: the frame loop (main.cpp) draws what it says with WarpRenderer.

#include <Eigen/Core>
#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geolens/io/image.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/measure/distortion.h"
#include "geolens/render/render.h"
#include "geolens/source/source_file.h"
#include "geolens/warp/warp_map.h"
#include "lens_solver.h"

namespace geolens::view {

/// What the panel shows of the frame on screen, measured once per answer (not per frame).
struct FrameMeasures {
  std::vector<double> zoom_measured;  ///< per lens of the frame, at its peak
  std::vector<int> flips;             ///< per lens: flipped triangles nearest to it
  int flipped = 0;                    ///< flipped triangles in all
  double conformal_mean = 0;          ///< area-weighted mean shape distortion, s1 / s2 - 1
  double conformal_max = 0;           ///< the largest finite one
  TriangleDistortion triangles;       ///< per triangle of the frame's warp
};

/// Measures the warp of `frame` (and its flips per lens of the frame).
FrameMeasures measure_frame(const SolvedFrame& frame);

/// The colour of each triangle in the shape-distortion heatmap, as `geolens compare` draws it
/// (annotate.h): heat_colour of its s1 / s2 - 1 over `max_value` (> 0), flipped triangles
/// kFlippedColour.
std::vector<std::array<uint8_t, 3>> heat_colours(const TriangleDistortion& triangles,
                                                 double max_value);

/// Mouse buttons and modifiers, as the window reports them (GLFW's values are not needed here).
enum class Button { kLeft, kRight };
struct Modifiers {
  bool ctrl = false, shift = false;
  bool double_click = false;  ///< a press that is the second of a double click
};

/// Throws InvalidInput naming "export" unless `path` ends in .txt, its folder exists and it is
/// not the file `input_image` (may be empty).
void check_export_path(const std::string& path, const std::string& input_image);

class Viewer {
 public:
  /// How long a frame waits for the answer to the lenses it has just submitted.
  static constexpr std::chrono::milliseconds kShowWait{4};

  /// `options` the geometric lens's; `method` one of method_names().
  Viewer(const LensOptions& options, const std::string& method);

  // --- the image ---
  /// Shows `image` (read from `path`); the lenses that no longer fit are dropped. Throws
  /// InvalidInput for an empty image.
  void open(Image image, const std::string& path);
  /// How open_file opens a source file (the frame of one without pixels, a map's style, a
  /// scene's camera, a volume's transfer function): the command line's.
  SourceFileOptions source_options;
  /// Reads `path`, an image or any source file open_source reads (source/source_file.h; with
  /// source_options, its whole frame rendered at zoom 1 with its overlay, open_frame), and shows
  /// it, on the calling thread (the command line's IMAGE, before the window opens). Throws
  /// InvalidInput when it cannot be read.
  void open_file(const std::string& path);
  /// open_file(path) off the UI thread (a SourceOpener): the current image stays shown, with
  /// status() saying so, until update() takes the answer and shows it as open_file would; on
  /// failure the current image is kept and the one-line reason goes to `message`. A later
  /// request (open or orbit) replaces one not answered yet. For the panel's Open field and a
  /// file dropped on the window.
  void try_open(const std::string& path);
  /// Turns the camera of a 3D source (a mesh or a volume, opened at source_options.view, by
  /// default azimuth 30 and elevation 20 degrees) about the scene by `d_azimuth` and `d_elevation`
  /// degrees (elevation kept in [-85, 85]) and asks for the new view, rendered again off the UI
  /// thread as try_open's open; the lenses stay where they are on the screen. Turns from the
  /// camera asked last, so that presses made while a view renders add up and only the newest
  /// camera is rendered; a failure is kept as try_open keeps it. For the arrow keys. Returns
  /// false, and does nothing, for any other source, or while a file is being opened.
  bool orbit(double d_azimuth, double d_elevation);
  /// "opening PATH ..." or "rendering view AZIMUTH,ELEVATION ..." while a try_open or orbit is
  /// under way; else empty.
  std::string status() const;
  /// The files opened and views rendered off the UI thread and shown so far, and how long the
  /// latest of them took to open and render (open_frame), milliseconds: for --stats.
  int opened_count() const { return opened_count_; }
  double opened_ms() const { return opened_ms_; }
  bool has_image() const { return image_.width > 0; }
  const Image& image() const { return image_; }
  const std::string& image_path() const { return image_path_; }
  std::uint64_t image_generation() const { return image_generation_; }

  // --- detail: a source finer than its frame (SourceFile::scale > 1: a vector map, an SVG) ---
  /// Whether the source shown has such detail (a plain image has none).
  bool has_detail() const { return bool(detail_worker_); }
  /// Shown while on (the default) and the source has detail: once the frame's warp is the full
  /// answer to the latest request (the lenses at rest: not a draft, nothing newer asked), it is
  /// rendered from the source on a worker thread at the resolution the window shows pane 0
  /// (render(warp, file, options), source_file.h: the finer levels and the overlay, as `geolens
  /// magnify` draws them), and that picture replaces the frame's pixels until the frame or the
  /// view changes. The right half of a split view shows the frame's pixels.
  bool detail = true;
  /// That picture, if one for the frame and the view shown is ready; else null (the frame's
  /// pixels are shown).
  const DetailPicture* detail_picture() const;
  /// Changes with every new picture taken from the worker.
  std::uint64_t detail_generation() const { return detail_generation_; }

  // --- lenses (numbered from 0 here; the script and panel number them from 1) ---
  const std::vector<Lens>& lenses() const { return lenses_; }
  /// Adds the lenses of a --lens spec (lens_spec.h); throws InvalidInput for a bad one.
  void add_lenses(const std::string& spec);
  void add_lens(const Lens& lens);
  void remove_lens(size_t index);
  /// Moves the lens so that its peak (a circle's centre) is at `peak`, source pixels, kept in
  /// the image. `dragging`: part of a drag (the solve under way finishes, see LensSolver).
  void move_lens(size_t index, const Eigen::Vector2d& peak, bool dragging);
  void set_zoom(size_t index, double zoom);      ///< clamped to [1, 8]
  void set_radius(size_t index, double radius);  ///< a polygon is scaled about its peak
  void select(std::optional<size_t> index) { selected_ = index; }
  std::optional<size_t> selected() const { return selected_; }
  /// Throws InvalidInput naming `what` unless `index` names a lens.
  void check_index(size_t index, const std::string& what) const;
  /// The lenses as --lens arguments (with --model and --mesh) for the CLI, and for a source that
  /// is not a plain image its frame (--size) and the options that framed it (--style, --view at
  /// the camera shown, --transfer), so `geolens magnify` frames it alike. A mask lens has no
  /// text form, and a polygon drawn or changed here has no file until export_lenses writes it:
  /// both are said in a comment.
  std::string lens_arguments() const;
  /// Writes lens_arguments() to `path` (a .txt file, never the input image), after writing each
  /// polygon lens without a file to PATH-STEM-lens-N.txt ('x y' per vertex, the polygon spec's
  /// format; N its number) and naming that file in its spec. Returns the arguments. Throws
  /// InvalidInput for a bad path, IoError if a file cannot be written.
  std::string export_lenses(const std::string& path);

  // --- drawing a polygon lens: click the vertices, double-click to close ---
  /// Starts drawing (the lens selection is dropped); a drawing under way starts again.
  void start_polygon();
  void cancel_polygon() { drawn_.reset(); }
  bool drawing_polygon() const { return drawn_.has_value(); }
  size_t polygon_vertices() const;  ///< clicked so far
  /// Where the vertices clicked so far are shown (through the frame's warp), then the pointer:
  /// window pixels, for the outline of the polygon being drawn. Empty when not drawing.
  std::vector<Eigen::Vector2d> polygon_outline();
  /// A polygon lens's outline as shown (a circle's the renderer draws): its edges cut into pieces
  /// of at most 2 source pixels and mapped through the frame's warp, window pixels, so that it
  /// bends with the picture; `selected` for the selected lens.
  struct Outline {
    std::vector<Eigen::Vector2d> points;  ///< closed, not repeated
    bool selected = false;
  };
  /// Those of the polygon lenses of the frame shown in `pane` (0; 1 the right half while split).
  std::vector<Outline> region_outlines(int pane = 0);

  // --- solver options ---
  void set_method(const std::string& method);
  void set_mesh(int mesh);
  void set_model(LensModel model);
  const std::string& method() const { return method_; }
  const LensOptions& options() const { return options_; }
  /// Split view: the window's left half shows the method, its right half `method` (one of
  /// method_names()) on the same lenses, each solved by a solver of its own; "" ends it.
  void set_split(const std::string& method);
  const std::string& split() const { return split_.method; }
  /// The right half's frame and its measures (while split).
  const SolvedFrame& split_frame() const { return split_.frame; }
  std::uint64_t split_generation() const { return split_.generation; }
  const FrameMeasures& split_measures() const { return split_.measures; }
  /// What pane 0 (the method) or 1 (the split) shows, for its label: "" (the current lenses),
  /// "waiting" (a frame of other lenses or options while its solver works on the current ones;
  /// a pane whose method was just switched shows the image as it is, not the last method's
  /// picture) or, for the split, "failed" (its method refuses the lenses: the image as it is,
  /// and `message` says why).
  std::string pane_state(int pane) const;

  // --- the view ---
  /// The window's framebuffer size, pixels; call before the input of each frame.
  void set_window(int width, int height);
  /// Window pixels per source pixel, and where the source's origin is in the window (in the
  /// left half, while split; the right half is pane_offset() further).
  double scale() const;
  Eigen::Vector2d origin() const;
  /// The width of the window's half while split (its left half: [0, pane_width())), else of all.
  int pane_width() const { return split_.method.empty() ? window_width_ : window_width_ / 2; }
  Eigen::Vector2d pane_offset() const { return {pane_width(), 0}; }
  void fit_view();

  // --- input, in window pixels ---
  void mouse_move(const Eigen::Vector2d& at);
  void mouse_button(Button button, bool pressed, Modifiers mods);
  void scroll(double dy, Modifiers mods);
  void delete_selected();
  /// The lens whose region holds the source point shown at window point `at`, if any.
  std::optional<size_t> lens_at(const Eigen::Vector2d& at);
  /// The source point shown at window point `at`, if the image is shown there.
  std::optional<Eigen::Vector2d> source_at(const Eigen::Vector2d& at);

  // --- per frame ---
  /// Shows a file opened or a view rendered off the UI thread, if it is ready; submits the lenses
  /// if they changed, then takes the solver's latest answer, then asks for the
  /// detail of the frame and view if they are at rest (`detail`). Returns true if the frame to
  /// draw changed.
  bool update();
  /// Blocks until a file being opened or a view being rendered (try_open, orbit) is shown, the
  /// solver has answered every request, and the detail render of its answer (if any) is done.
  void wait_idle();
  const SolvedFrame& frame() const { return frame_; }
  std::uint64_t frame_generation() const { return frame_generation_; }
  const FrameMeasures& measures() const { return measures_; }
  /// When the request the frame answers was made (for move-to-shown latency).
  std::chrono::steady_clock::time_point frame_requested_at() const { return frame_requested_at_; }

  /// The heatmap's red end, s1 / s2 - 1; by default the largest the frames show (as `geolens
  /// compare` scales to the largest of the methods it shows).
  double heat_max() const;
  void set_heat_max(double value);  ///< >= 0; 0: the largest shown

  bool wireframe = false;
  bool heatmap = false;  ///< the shape-distortion heatmap over the picture
  bool outlines = true;
  bool panel = true;
  std::string message;  ///< the latest problem to show in the panel (a bad file, a failed solve)

 private:
  void changed(bool dragging);
  // Puts `region` in lens `index` (validated as a lens on the image), or throws InvalidInput
  // naming `what` that this kind of lens cannot be `done` when it is empty.
  void replace_region(size_t index, const std::optional<Region>& region, const char* what,
                      const char* done);
  void restart_solver();
  // Pane 0 (the method) or 1 (the split) shows the image as it is until its solver answers.
  void show_identity(int pane);
  // The view of pane 0 a detail picture is wanted for now, if any (detail).
  std::optional<DetailView> detail_view() const;
  // Asks for the detail of the frame and view at rest, and takes the worker's latest picture.
  void update_detail();
  // The pane (0 left, 1 right while split) at window point `at`, and `at` in the left pane's
  // window coordinates.
  std::pair<int, Eigen::Vector2d> pane_at(const Eigen::Vector2d& at) const;
  // Adds the vertex under the pointer, or on a double click closes the polygon into a lens.
  void polygon_click(bool double_click);
  const WarpMap* warp_map(int pane = 0);

  // Shows the whole frame of a source opened (open_file), and its camera when it is a 3D scene:
  // `azimuth` and `elevation` for an orbit, else source_options.view's.
  void show_source(OpenedSource opened, std::optional<std::pair<double, double>> camera);
  // Takes the opener's answer to the latest request, if it is ready, and shows it (or its
  // failure in `message`). Returns true if the image changed.
  bool take_opened();

  Image image_;
  std::string image_path_;
  // The detail renders of the source file shown, when it has detail (has_detail).
  std::unique_ptr<DetailWorker> detail_worker_;
  std::optional<DetailView> detail_asked_;       // the view of the latest detail request
  std::shared_ptr<const DetailPicture> detail_;  // the worker's latest picture
  std::uint64_t detail_generation_ = 0;
  std::uint64_t submitted_request_ = 0;  // the solver's latest request
  bool orbits_ = false;                  // the source is a 3D scene (orbit)
  std::string source_kind_;              // SourceFile::kind of the source shown
  double azimuth_ = 0, elevation_ = 0;   // its camera, degrees
  // The open or orbit asked off the UI thread and not shown yet.
  struct Asked {
    std::uint64_t request = 0;  // the opener's
    std::string path;
    std::optional<std::pair<double, double>> camera;  // an orbit's azimuth and elevation
  };
  std::unique_ptr<SourceOpener> opener_;  // made at the first request
  std::optional<Asked> asked_;
  int opened_count_ = 0;
  double opened_ms_ = 0;
  std::uint64_t image_generation_ = 0;
  std::vector<Lens> lenses_;
  std::vector<std::string> specs_;  // per lens: its --lens text, or "" once it has none
  std::optional<size_t> selected_;
  LensOptions options_;
  std::string method_;
  std::unique_ptr<LensSolver> solver_;
  bool dirty_ = false, drop_stale_ = false;
  std::uint64_t accepted_request_ = 0;  // the solver's request frame_ answers
  std::vector<std::pair<std::uint64_t, std::chrono::steady_clock::time_point>> requested_at_;

  SolvedFrame frame_;
  std::uint64_t frame_generation_ = 0;  // changes with every new frame to draw
  std::chrono::steady_clock::time_point frame_requested_at_;
  FrameMeasures measures_;
  std::optional<WarpMap> map_;  // of frame_, built on the first pick
  std::uint64_t map_generation_ = 0;

  // The right half of a split view: its own solver, frame and map.
  struct Split {
    std::string method;  // "" while not split
    std::unique_ptr<LensSolver> solver;
    std::uint64_t submitted = 0;  // the solver's latest request
    bool failed = false;          // its latest request was refused
    SolvedFrame frame;
    std::uint64_t generation = 0;
    FrameMeasures measures;
    std::optional<WarpMap> map;
    std::uint64_t map_generation = 0;
  };
  Split split_;
  double heat_max_ = 0;
  int window_width_ = 1, window_height_ = 1;
  double view_zoom_ = 1;
  Eigen::Vector2d pan_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d mouse_ = Eigen::Vector2d::Zero();
  std::optional<size_t> dragged_;
  Eigen::Vector2d drag_from_ = Eigen::Vector2d::Zero(), drag_peak_ = Eigen::Vector2d::Zero();
  bool panning_ = false;
  std::optional<std::vector<Eigen::Vector2d>> drawn_;  // the polygon being drawn, source pixels
};

}  // namespace geolens::view
