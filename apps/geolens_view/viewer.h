#pragma once
// The viewer's state and what the user does to it: the image, the lenses, the view of the
// whole picture (pan and zoom), the selection, and the mouse and keys that change them. Holds
// no GL: the frame loop (main.cpp) draws what it says with WarpRenderer.

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geolens/io/image.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/warp/warp_map.h"
#include "lens_solver.h"

namespace geolens::view {

/// What the panel shows of the frame on screen, measured once per answer (not per frame).
struct FrameMeasures {
  std::vector<double> zoom_measured;  ///< per lens of the frame, at its peak
  std::vector<int> flips;             ///< per lens: flipped triangles nearest to it
  int flipped = 0;                    ///< flipped triangles in all
  double conformal_mean = 0;          ///< area-weighted mean shape distortion, s1 / s2 - 1
};

/// Mouse buttons and modifiers, as the window reports them (GLFW's values are not needed here).
enum class Button { kLeft, kRight };
struct Modifiers {
  bool ctrl = false, shift = false;
};

class Viewer {
 public:
  /// `options` the geometric lens's; `method` one of method_names().
  Viewer(const LensOptions& options, const std::string& method);

  // --- the image ---
  /// Shows `image` (read from `path`); the lenses that no longer fit are dropped. Throws
  /// InvalidInput for an empty image.
  void open(Image image, const std::string& path);
  /// Reads `path` and shows it; on failure keeps the current image and returns the one-line
  /// reason (empty on success). For the panel's Open field and a file dropped on the window.
  std::string try_open(const std::string& path);
  bool has_image() const { return image_.width > 0; }
  const Image& image() const { return image_; }
  const std::string& image_path() const { return image_path_; }
  std::uint64_t image_generation() const { return image_generation_; }

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
  /// The lenses as --lens arguments (with --model and --mesh) for the CLI. A mask lens has no
  /// text form and a moved polygon no file: both are said in a comment.
  std::string lens_arguments() const;

  // --- solver options ---
  void set_method(const std::string& method);
  void set_mesh(int mesh);
  void set_model(LensModel model);
  const std::string& method() const { return method_; }
  const LensOptions& options() const { return options_; }

  // --- the view ---
  /// The window's framebuffer size, pixels; call before the input of each frame.
  void set_window(int width, int height);
  /// Window pixels per source pixel, and where the source's origin is in the window.
  double scale() const;
  Eigen::Vector2d origin() const;
  void fit_view();

  // --- input, in window pixels ---
  void mouse_move(const Eigen::Vector2d& at);
  void mouse_button(Button button, bool pressed, Modifiers mods);
  void scroll(double dy, Modifiers mods);
  void delete_selected();
  /// The lens whose region holds the source point shown at window point `at`, if any.
  std::optional<size_t> lens_at(const Eigen::Vector2d& at);

  // --- per frame ---
  /// Submits the lenses if they changed, then takes the solver's latest answer. Returns true if
  /// the frame to draw changed.
  bool update();
  void wait_idle();  ///< blocks until the solver has answered every request
  const SolvedFrame& frame() const { return frame_; }
  std::uint64_t frame_generation() const { return frame_generation_; }
  const FrameMeasures& measures() const { return measures_; }
  /// When the request the frame answers was made (for move-to-shown latency).
  std::chrono::steady_clock::time_point frame_requested_at() const { return frame_requested_at_; }

  bool wireframe = false;
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
  const WarpMap* warp_map();
  void measure();

  Image image_;
  std::string image_path_;
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

  int window_width_ = 1, window_height_ = 1;
  double view_zoom_ = 1;
  Eigen::Vector2d pan_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d mouse_ = Eigen::Vector2d::Zero();
  std::optional<size_t> dragged_;
  Eigen::Vector2d drag_from_ = Eigen::Vector2d::Zero(), drag_peak_ = Eigen::Vector2d::Zero();
  bool panning_ = false;
};

}  // namespace geolens::view
