#pragma once
// The window: GLFW, an OpenGL 3.3 core context (functions through libepoxy) and Dear ImGui on
// it. The one object that holds what GLFW keeps globally (its error callback, init and
// terminate); everything else reaches the window through it.

#include <Eigen/Core>
#include <stdexcept>
#include <string>

#include "geolens/io/image.h"
#include "viewer.h"

struct GLFWwindow;

namespace geolens::view {

/// No display, no OpenGL 3.3 core context: the viewer cannot start. main() says why in one line.
struct WindowError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Keys the viewer acts on.
enum class Key {
  kDelete,
  kFit,
  kWireframe,
  kHeatmap,
  kPolygon,
  kEscape,
  kLeft,  // the arrow keys
  kRight,
  kUp,
  kDown
};

/// What the window reports, in framebuffer pixels (origin top-left, y down). Events ImGui takes
/// (the pointer over the panel, typing in a field) are not reported, except button releases.
class WindowInput {
 public:
  virtual ~WindowInput() = default;
  virtual void mouse_move(const Eigen::Vector2d& at) = 0;
  virtual void mouse_button(Button button, bool pressed, Modifiers mods) = 0;
  virtual void scroll(double dy, Modifiers mods) = 0;
  virtual void key(Key key) = 0;
  virtual void drop(const std::string& path) = 0;
};

class Window {
 public:
  /// Opens a width x height window (screen pixels) titled `title`; `vsync` paces frames to the
  /// display, off for scripted runs. Throws WindowError naming what failed (GLFW's own message:
  /// no display, no OpenGL 3.3 core).
  Window(int width, int height, const std::string& title, bool vsync);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  /// Where input goes (not owned; null: nowhere).
  void set_input(WindowInput* input) { input_ = input; }
  bool should_close() const;
  void poll();
  void swap();
  int framebuffer_width() const;
  int framebuffer_height() const;
  /// Starts and ends an ImGui frame; draw the panel between them. end_ui() renders it.
  void begin_ui();
  void end_ui();
  /// The back buffer as an RGB image: call after drawing and before swap() (the front buffer is
  /// not reliable after a swap).
  Image read_back_buffer() const;
  /// The OpenGL version and renderer, for messages ("4.5 (Core Profile) Mesa 22.3.6, llvmpipe").
  std::string gl_description() const;

 private:
  static void on_error(int code, const char* description);
  static Window& of(GLFWwindow* window);
  Eigen::Vector2d to_framebuffer(double x, double y) const;
  Modifiers modifiers() const;

  static std::string last_error_;  // GLFW reports errors to a free function: kept here
  GLFWwindow* window_ = nullptr;
  WindowInput* input_ = nullptr;
  // The last left press, seconds (glfwGetTime) and screen pixels: a double click is a second
  // press soon after and near it.
  double left_pressed_at_ = -1;
  Eigen::Vector2d left_pressed_where_ = Eigen::Vector2d::Zero();
};

}  // namespace geolens::view
