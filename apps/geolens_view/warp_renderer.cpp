#include "warp_renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>

#include "geolens/source/mip_pyramid.h"

namespace geolens::view {

namespace {

// Window pixels (origin top-left, y down) to clip space.
const char* const kVertexShader = R"(#version 330 core
layout(location = 0) in vec2 a_screen;  // the warp's screen position, its frame's pixels
layout(location = 1) in vec2 a_source;  // source pixels
uniform vec2 u_origin;
uniform float u_scale;
uniform vec2 u_window;
out vec2 v_source;
void main() {
  vec2 p = u_origin + a_screen * u_scale;
  gl_Position = vec4(2.0 * p.x / u_window.x - 1.0, 1.0 - 2.0 * p.y / u_window.y, 0.0, 1.0);
  v_source = a_source;
}
)";

// The texture at the source point; circle outlines where the source point is within about a
// screen pixel of a circle (fwidth: how far the distance changes across one pixel).
const char* const kFragmentShader = R"(#version 330 core
in vec2 v_source;
uniform sampler2D u_texture;
uniform vec2 u_size;  // source pixels
uniform int u_flat;
uniform vec4 u_colour;
uniform int u_count;
uniform vec3 u_circles[32];
uniform int u_selected;
out vec4 o_colour;
void main() {
  if (u_flat != 0) {
    o_colour = u_colour;
    return;
  }
  vec4 c = texture(u_texture, v_source / u_size);
  for (int i = 0; i < u_count; ++i) {
    float d = length(v_source - u_circles[i].xy);
    float e = abs(d - u_circles[i].z) / max(fwidth(d), 1e-6);
    // A line about two pixels wide, faded out over a third, over a faint dark halo.
    vec3 ring = i == u_selected ? vec3(1.0, 0.55, 0.1) : vec3(1.0);
    c.rgb = mix(c.rgb * 0.6, c.rgb, smoothstep(1.0, 2.5, e));
    c.rgb = mix(ring, c.rgb, smoothstep(0.7, 1.3, e));
    if (e < 2.5) c.a = 1.0;
  }
  o_colour = c;
}
)";

unsigned compile(GLenum kind, const char* text) {
  const GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw std::runtime_error(std::string("WarpRenderer: a shader does not compile: ") + log);
  }
  return shader;
}

}  // namespace

WarpRenderer::WarpRenderer() {
  const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader);
  const GLuint fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(program_, sizeof log, nullptr, log);
    glDeleteProgram(program_);
    throw std::runtime_error(std::string("WarpRenderer: the shaders do not link: ") + log);
  }
  loc_origin_ = glGetUniformLocation(program_, "u_origin");
  loc_scale_ = glGetUniformLocation(program_, "u_scale");
  loc_window_ = glGetUniformLocation(program_, "u_window");
  loc_size_ = glGetUniformLocation(program_, "u_size");
  loc_flat_ = glGetUniformLocation(program_, "u_flat");
  loc_colour_ = glGetUniformLocation(program_, "u_colour");
  loc_count_ = glGetUniformLocation(program_, "u_count");
  loc_circles_ = glGetUniformLocation(program_, "u_circles");
  loc_selected_ = glGetUniformLocation(program_, "u_selected");
  glUseProgram(program_);
  glUniform1i(glGetUniformLocation(program_, "u_texture"), 0);

  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glGenBuffers(1, &ebo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 4 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 4 * sizeof(float),
                        reinterpret_cast<const void*>(2 * sizeof(float)));
  glBindVertexArray(0);
  glGenTextures(1, &texture_);
}

WarpRenderer::~WarpRenderer() {
  glDeleteTextures(1, &texture_);
  glDeleteBuffers(1, &ebo_);
  glDeleteBuffers(1, &vbo_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteProgram(program_);
}

void WarpRenderer::set_image(const Image& image) {
  GLint max_side = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
  image_width_ = image.width;
  image_height_ = image.height;
  const Image* upload = &image;
  std::optional<MipPyramid> pyramid;  // only for an image larger than one texture
  if (std::max(image.width, image.height) > max_side) {
    pyramid.emplace(image);
    int level = 0;
    while (std::max(pyramid->level_width(level), pyramid->level_height(level)) > max_side) ++level;
    upload = &pyramid->level(level);
  }
  static constexpr GLenum kFormats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
  static constexpr GLenum kInternal[] = {GL_R8, GL_RG8, GL_RGB8, GL_RGBA8};
  // Grey (+ alpha) shown as grey: the red channel in red, green and blue.
  static constexpr GLint kSwizzles[4][4] = {{GL_RED, GL_RED, GL_RED, GL_ONE},
                                            {GL_RED, GL_RED, GL_RED, GL_GREEN},
                                            {GL_RED, GL_GREEN, GL_BLUE, GL_ONE},
                                            {GL_RED, GL_GREEN, GL_BLUE, GL_ALPHA}};
  const int c = upload->channels - 1;
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GLint(kInternal[c]), upload->width, upload->height, 0, kFormats[c],
               GL_UNSIGNED_BYTE, upload->pixels.data());
  glTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_RGBA, kSwizzles[c]);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glGenerateMipmap(GL_TEXTURE_2D);
}

void WarpRenderer::set_mesh(const WarpMesh& mesh) {
  std::vector<float> vertices(size_t(mesh.source.rows()) * 4);
  for (Eigen::Index v = 0; v < mesh.source.rows(); ++v) {
    float* p = vertices.data() + v * 4;
    p[0] = float(mesh.screen(v, 0));
    p[1] = float(mesh.screen(v, 1));
    p[2] = float(mesh.source(v, 0));
    p[3] = float(mesh.source(v, 1));
  }
  std::vector<unsigned> indices(size_t(mesh.F.rows()) * 3);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) indices[size_t(f) * 3 + k] = unsigned(mesh.F(f, k));
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(float)), vertices.data(),
               GL_STREAM_DRAW);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(unsigned)),
               indices.data(), GL_STREAM_DRAW);
  glBindVertexArray(0);
  index_count_ = int(indices.size());
}

void WarpRenderer::draw(const DrawSettings& s) const {
  glViewport(0, 0, s.window_width, s.window_height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glClearColor(0.16f, 0.16f, 0.17f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (index_count_ == 0) return;
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glUseProgram(program_);
  glUniform2f(loc_origin_, float(s.origin.x()), float(s.origin.y()));
  glUniform1f(loc_scale_, float(s.scale));
  glUniform2f(loc_window_, float(s.window_width), float(s.window_height));
  glUniform2f(loc_size_, float(image_width_), float(image_height_));
  std::vector<float> circles;
  for (const Eigen::Vector3d& c : s.outlines)
    if (circles.size() < 3 * kMaxOutlines)
      circles.insert(circles.end(), {float(c.x()), float(c.y()), float(c.z())});
  glUniform1i(loc_count_, GLint(circles.size() / 3));
  if (!circles.empty()) glUniform3fv(loc_circles_, GLsizei(circles.size() / 3), circles.data());
  glUniform1i(loc_selected_, s.selected);
  glUniform1i(loc_flat_, 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
  if (s.wireframe) {
    glUniform1i(loc_flat_, 1);
    glUniform4f(loc_colour_, 0.1f, 0.9f, 0.9f, 0.45f);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
  glBindVertexArray(0);
  glDisable(GL_BLEND);
}

}  // namespace geolens::view
