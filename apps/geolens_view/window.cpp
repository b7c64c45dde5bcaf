#include "window.h"

#include <epoxy/gl.h>
// GLFW after epoxy, which defines the GL headers GLFW would otherwise include.
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

namespace geolens::view {

std::string Window::last_error_;

void Window::on_error(int, const char* description) { last_error_ = description; }

Window& Window::of(GLFWwindow* window) {
  return *static_cast<Window*>(glfwGetWindowUserPointer(window));
}

Window::Window(int width, int height, const std::string& title, bool vsync) {
  glfwSetErrorCallback(&Window::on_error);
  last_error_.clear();
  if (!glfwInit()) throw WindowError("cannot open a window: " + last_error_);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw WindowError("cannot create an OpenGL 3.3 core context: " + last_error_);
  }
  glfwMakeContextCurrent(window_);
  if (epoxy_gl_version() < 33) {
    const std::string version = gl_description();
    glfwDestroyWindow(window_);
    glfwTerminate();
    throw WindowError("OpenGL 3.3 is needed, the context has " + version);
  }
  glfwSwapInterval(vsync ? 1 : 0);
  glfwSetWindowUserPointer(window_, this);
  // Ours first: ImGui's backend installs its own and calls these after them.
  glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
    Window& self = of(w);
    if (self.input_) self.input_->mouse_move(self.to_framebuffer(x, y));
  });
  glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
    Window& self = of(w);
    if (!self.input_ || (button != GLFW_MOUSE_BUTTON_LEFT && button != GLFW_MOUSE_BUTTON_RIGHT))
      return;
    const bool pressed = action == GLFW_PRESS;
    if (pressed && ImGui::GetIO().WantCaptureMouse) return;
    Modifiers mods = self.modifiers();
    if (pressed && button == GLFW_MOUSE_BUTTON_LEFT) {
      // GLFW has no double click: ImGui's own thresholds (time, distance) make one.
      const ImGuiIO& io = ImGui::GetIO();
      Eigen::Vector2d at;
      glfwGetCursorPos(w, &at.x(), &at.y());
      const double now = glfwGetTime();
      mods.double_click = self.left_pressed_at_ >= 0 &&
                          now - self.left_pressed_at_ < io.MouseDoubleClickTime &&
                          (at - self.left_pressed_where_).norm() < io.MouseDoubleClickMaxDist;
      // A third press starts a new pair.
      self.left_pressed_at_ = mods.double_click ? -1 : now;
      self.left_pressed_where_ = at;
    }
    self.input_->mouse_button(button == GLFW_MOUSE_BUTTON_LEFT ? Button::kLeft : Button::kRight,
                              pressed, mods);
  });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
    Window& self = of(w);
    if (self.input_ && !ImGui::GetIO().WantCaptureMouse) self.input_->scroll(dy, self.modifiers());
  });
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
    Window& self = of(w);
    if (!self.input_ || action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
    if (key == GLFW_KEY_DELETE || key == GLFW_KEY_BACKSPACE) self.input_->key(Key::kDelete);
    if (key == GLFW_KEY_F) self.input_->key(Key::kFit);
    if (key == GLFW_KEY_W) self.input_->key(Key::kWireframe);
    if (key == GLFW_KEY_H) self.input_->key(Key::kHeatmap);
    if (key == GLFW_KEY_P) self.input_->key(Key::kPolygon);
    if (key == GLFW_KEY_ESCAPE) self.input_->key(Key::kEscape);
    if (key == GLFW_KEY_LEFT) self.input_->key(Key::kLeft);
    if (key == GLFW_KEY_RIGHT) self.input_->key(Key::kRight);
    if (key == GLFW_KEY_UP) self.input_->key(Key::kUp);
    if (key == GLFW_KEY_DOWN) self.input_->key(Key::kDown);
  });
  glfwSetDropCallback(window_, [](GLFWwindow* w, int count, const char** paths) {
    Window& self = of(w);
    if (self.input_ && count > 0) self.input_->drop(paths[0]);
  });
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working folder
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
}

Window::~Window() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window_);
  glfwTerminate();
}

bool Window::should_close() const { return glfwWindowShouldClose(window_); }
void Window::poll() { glfwPollEvents(); }
void Window::swap() { glfwSwapBuffers(window_); }

int Window::framebuffer_width() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return w;
}

int Window::framebuffer_height() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return h;
}

Eigen::Vector2d Window::to_framebuffer(double x, double y) const {
  int ww = 0, wh = 0, fw = 0, fh = 0;
  glfwGetWindowSize(window_, &ww, &wh);
  glfwGetFramebufferSize(window_, &fw, &fh);
  return {ww > 0 ? x * fw / ww : x, wh > 0 ? y * fh / wh : y};
}

Modifiers Window::modifiers() const {
  Modifiers m;
  m.ctrl = glfwGetKey(window_, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
           glfwGetKey(window_, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
  m.shift = glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
            glfwGetKey(window_, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
  return m;
}

void Window::begin_ui() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void Window::end_ui() {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

Image Window::read_back_buffer() const {
  const int w = framebuffer_width(), h = framebuffer_height();
  Image flipped(w, h, 3);
  glFinish();
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, flipped.pixels.data());
  Image image(w, h, 3);
  const size_t row = size_t(w) * 3;
  for (int y = 0; y < h; ++y)
    std::copy_n(flipped.pixels.data() + size_t(h - 1 - y) * row, row, image.at(0, y));
  return image;
}

std::string Window::gl_description() const {
  const auto text = [](GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return text(GL_VERSION) + ", " + text(GL_RENDERER);
}

}  // namespace geolens::view
