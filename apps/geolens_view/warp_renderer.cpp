#include "warp_renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "geolens/source/source.h"

namespace geolens::view {

namespace {

// Window pixels (origin top-left, y down) to clip space.
const char* const kVertexShader = R"(#version 330 core
layout(location = 0) in vec2 a_screen;  // the warp's screen position, its frame's pixels
layout(location = 1) in vec2 a_source;  // source pixels
layout(location = 2) in vec3 a_heat;    // the heatmap's colour (its pass only)
uniform vec2 u_origin;
uniform float u_scale;
uniform vec2 u_window;
uniform float u_flip;  // -1: into a texture, rows top down like the window's (WarpRenderer::redraw)
uniform float u_depth;  // 0: the moving triangles, in front of the in-place quad's 0.5
out vec2 v_source;
out vec3 v_heat;
out vec2 v_window;
void main() {
  vec2 p = u_origin + a_screen * u_scale;
  v_window = p;
  gl_Position =
      vec4(2.0 * p.x / u_window.x - 1.0, u_flip * (1.0 - 2.0 * p.y / u_window.y), u_depth, 1.0);
  v_source = a_source;
  v_heat = a_heat;
}
)";

// The texture at the source point, or the detail picture at the window point (in the heatmap pass,
// its luminance under the triangle's colour); circle outlines where the source point is within
// about a screen pixel of a circle (fwidth: how far the distance changes across one pixel).
const char* const kFragmentShader = R"(#version 330 core
in vec2 v_source;
in vec3 v_heat;
in vec2 v_window;
uniform float u_heat;  // the heatmap's opacity; 0: the picture
uniform sampler2D u_texture;
uniform vec2 u_size;  // source pixels
uniform int u_flat;
uniform vec4 u_colour;
uniform int u_count;
uniform vec3 u_circles[32];
uniform int u_selected;
uniform int u_detail;
uniform sampler2D u_detail_texture;
uniform vec4 u_detail_area;  // the window pixels it covers: x, y, width, height
out vec4 o_colour;
void main() {
  if (u_flat != 0) {
    o_colour = u_colour;
    return;
  }
  vec4 c = u_detail != 0
               ? texture(u_detail_texture, (v_window - u_detail_area.xy) / u_detail_area.zw)
               : texture(u_texture, v_source / u_size);
  if (u_heat > 0.0) {
    float grey = dot(c.rgb, vec3(0.299, 0.587, 0.114));
    c = vec4(u_heat * v_heat + (1.0 - u_heat) * vec3(grey), 1.0);
  }
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

// Texel formats by channel count - 1.
constexpr GLenum kFormats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
constexpr GLenum kInternal[] = {GL_R8, GL_RG8, GL_RGB8, GL_RGBA8};
// Grey (+ alpha) shown as grey: the red channel in red, green and blue.
constexpr GLint kSwizzles[4][4] = {{GL_RED, GL_RED, GL_RED, GL_ONE},
                                   {GL_RED, GL_RED, GL_RED, GL_GREEN},
                                   {GL_RED, GL_GREEN, GL_BLUE, GL_ONE},
                                   {GL_RED, GL_GREEN, GL_BLUE, GL_ALPHA}};

// The background the window is cleared to, and a cached picture before it is drawn.
constexpr float kBackground[4] = {0.16f, 0.16f, 0.17f, 1.0f};

// A vertex at most this far from its source position (source pixels) is in place: far below
// what a picture shows, and below a float's resolution at the largest image side.
constexpr double kInPlace = 1e-4;

using Rect = WarpRenderer::Rect;

Rect intersection(const Rect& a, const Rect& b) {
  const int x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
  const int x1 = std::min(a.x + a.width, b.x + b.width),
            y1 = std::min(a.y + a.height, b.y + b.height);
  return {x0, y0, std::max(x1 - x0, 0), std::max(y1 - y0, 0)};
}

Rect united(const Rect& a, const Rect& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  const int x0 = std::min(a.x, b.x), y0 = std::min(a.y, b.y);
  const int x1 = std::max(a.x + a.width, b.x + b.width),
            y1 = std::max(a.y + a.height, b.y + b.height);
  return {x0, y0, x1 - x0, y1 - y0};
}

// The window pixels that `box` (the warp's screen pixels) touches, `margin` pixels more on
// every side.
Rect window_rect(const DrawSettings& s, const Eigen::AlignedBox2d& box, int margin) {
  if (box.isEmpty()) return {};
  const Eigen::Vector2d lo = s.origin + box.min() * s.scale, hi = s.origin + box.max() * s.scale;
  // Far beyond the window is clamped before the conversion to int.
  const auto clamp = [](double v) { return std::clamp(v, -1e6, 1e6); };
  const int x0 = int(std::floor(clamp(lo.x()))) - margin,
            y0 = int(std::floor(clamp(lo.y()))) - margin;
  const int x1 = int(std::ceil(clamp(hi.x()))) + margin,
            y1 = int(std::ceil(clamp(hi.y()))) + margin;
  return {x0, y0, x1 - x0, y1 - y0};
}

// Whether a and b draw the same picture but for its outlines and the warp.
bool same_view(const DrawSettings& a, const DrawSettings& b) {
  return a.window_width == b.window_width && a.window_height == b.window_height &&
         a.origin == b.origin && a.scale == b.scale && a.clip_x == b.clip_x &&
         a.clip_width == b.clip_width && a.pane == b.pane && a.wireframe == b.wireframe &&
         a.heatmap == b.heatmap && a.heat_opacity == b.heat_opacity && a.detail == b.detail;
}

bool same_outlines(const DrawSettings& a, const DrawSettings& b) {
  return a.outlines == b.outlines && a.selected == b.selected;
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
  loc_heat_ = glGetUniformLocation(program_, "u_heat");
  loc_flip_ = glGetUniformLocation(program_, "u_flip");
  loc_depth_ = glGetUniformLocation(program_, "u_depth");
  loc_detail_ = glGetUniformLocation(program_, "u_detail");
  loc_detail_area_ = glGetUniformLocation(program_, "u_detail_area");
  glUseProgram(program_);
  glUniform1i(glGetUniformLocation(program_, "u_texture"), 0);
  glUniform1i(glGetUniformLocation(program_, "u_detail_texture"), 1);

  // The picture's vertices: screen, source (4 floats); the heatmap's: the same and its colour
  // (4 bytes, normalized).
  constexpr GLsizei kHeatStride = 4 * sizeof(float) + 4;
  // A vertex array and its buffer, bound, with the screen and source positions (attributes 0
  // and 1) at the start of each vertex of `stride` bytes.
  auto positions = [](unsigned& vao, unsigned& vbo, GLsizei stride) {
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(2 * sizeof(float)));
  };
  for (Mesh& m : panes_) {
    positions(m.vao, m.vbo, 4 * sizeof(float));
    glGenBuffers(1, &m.ebo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ebo);
    positions(m.quad_vao, m.quad_vbo, 4 * sizeof(float));
    positions(m.heat_vao, m.heat_vbo, kHeatStride);
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 3, GL_UNSIGNED_BYTE, GL_TRUE, kHeatStride,
                          reinterpret_cast<const void*>(4 * sizeof(float)));
  }
  glBindVertexArray(0);
  glGenTextures(1, &texture_);
  glGenTextures(1, &detail_texture_);
}

WarpRenderer::~WarpRenderer() {
  glDeleteTextures(1, &detail_texture_);
  glDeleteTextures(1, &texture_);
  for (Cache& c : caches_) {
    glDeleteFramebuffers(1, &c.framebuffer);
    glDeleteTextures(1, &c.texture);
    glDeleteRenderbuffers(1, &c.depth);
  }
  for (Mesh& m : panes_) {
    glDeleteBuffers(1, &m.quad_vbo);
    glDeleteVertexArrays(1, &m.quad_vao);
    glDeleteBuffers(1, &m.heat_vbo);
    glDeleteVertexArrays(1, &m.heat_vao);
    glDeleteBuffers(1, &m.ebo);
    glDeleteBuffers(1, &m.vbo);
    glDeleteVertexArrays(1, &m.vao);
  }
  glDeleteProgram(program_);
}

void WarpRenderer::set_image(const Image& image) {
  GLint max_side = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
  const int side = std::min(int(max_side), kMaxTextureSide);
  const auto fits = [&](int w, int h) {
    return std::max(w, h) <= side &&
           size_t(w) * size_t(h) * size_t(image.channels) <= kTextureBytes;
  };
  texture_level_ = 0;
  TexelRegion texels{image.pixels.data(),
                     size_t(image.width) * size_t(image.channels),
                     0,
                     0,
                     image.width,
                     image.height,
                     image.channels,
                     {}};
  if (!fits(image.width, image.height)) {
    // The finest level that fits, made tile by tile through a tiled source over the image (each
    // level from the one below, in the LRU cache's budget): the pyramid is never held whole.
    TiledSourceOptions options;
    options.tile_size = 512;
    options.downsample_levels = true;
    const TiledSource tiled(
        image.width, image.height, image.channels,
        [&image](const TileRequest& r) {
          Image tile(r.width, r.height, r.channels);
          for (int j = 0; j < r.height; ++j)
            std::copy_n(image.at(r.x, r.y + j), size_t(r.width) * size_t(r.channels),
                        tile.at(0, j));
          return tile;
        },
        options);
    texture_level_ = 1;
    while (!fits(tiled.level_width(texture_level_), tiled.level_height(texture_level_)))
      ++texture_level_;
    texels = tiled.fetch(texture_level_, 0, 0, tiled.level_width(texture_level_),
                         tiled.level_height(texture_level_));
  }
  texture_width_ = texels.width;
  texture_height_ = texels.height;
  const int c = texels.channels - 1;
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, GLint(texels.stride / size_t(texels.channels)));
  glTexImage2D(GL_TEXTURE_2D, 0, GLint(kInternal[c]), texels.width, texels.height, 0, kFormats[c],
               GL_UNSIGNED_BYTE, texels.data);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_RGBA, kSwizzles[c]);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glGenerateMipmap(GL_TEXTURE_2D);
  // The quad shows the image in place under the triangles that move: only where they hide it.
  opaque_ = true;
  if (texels.channels == 2 || texels.channels == 4)
    for (int y = 0; opaque_ && y < texels.height; ++y) {
      const uint8_t* row = texels.data + size_t(y) * texels.stride;
      for (int x = 0; x < texels.width; ++x)
        if (row[size_t(x) * size_t(texels.channels) + size_t(texels.channels) - 1] != 255) {
          opaque_ = false;
          break;
        }
    }
  ++image_version_;
}

void WarpRenderer::set_detail(const Image& picture, const Rect& at) {
  const int c = picture.channels - 1;
  glBindTexture(GL_TEXTURE_2D, detail_texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GLint(kInternal[c]), picture.width, picture.height, 0, kFormats[c],
               GL_UNSIGNED_BYTE, picture.pixels.data());
  glTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_RGBA, kSwizzles[c]);
  // A texel per window pixel, sampled at its centre: linear filtering returns it as it is.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  detail_area_ = at;
  ++detail_version_;
}

void WarpRenderer::set_mesh(int pane, const WarpMesh& mesh) {
  const Eigen::Index n = mesh.source.rows();
  std::vector<float> vertices(size_t(n) * 4);
  std::vector<char> in_place(static_cast<size_t>(n));
  Mesh& m = panes_.at(size_t(pane));
  Eigen::AlignedBox2d box;  // the source's
  m.extent.setEmpty();
  for (Eigen::Index v = 0; v < n; ++v) {
    float* p = vertices.data() + v * 4;
    p[0] = float(mesh.screen(v, 0));
    p[1] = float(mesh.screen(v, 1));
    p[2] = float(mesh.source(v, 0));
    p[3] = float(mesh.source(v, 1));
    in_place[size_t(v)] =
        (mesh.screen.row(v) - mesh.source.row(v)).cwiseAbs().maxCoeff() <= kInPlace;
    box.extend(mesh.source.row(v).transpose());
    m.extent.extend(mesh.screen.row(v).transpose());
  }
  m.extent.extend(box);
  // The quad stands for the triangles in place if the source's triangles cover their box (their
  // areas add up to its area: they never overlap) and its border is in place: the picture of the
  // box is then the box (a map that keeps a disk's border covers the disk), the moving triangles
  // over the image in place.
  double area = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector2d a = mesh.source.row(mesh.F(f, 0)), b = mesh.source.row(mesh.F(f, 1)),
                          c = mesh.source.row(mesh.F(f, 2));
    area += 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
  }
  const double box_area = box.isEmpty() ? 0 : box.volume();
  m.quad = box_area > 0 && std::abs(area - box_area) <= 1e-9 * box_area;
  for (Eigen::Index v = 0; m.quad && v < n; ++v) {
    const Eigen::Vector2d p = mesh.source.row(v);
    const bool on_border = p.x() <= box.min().x() || p.y() <= box.min().y() ||
                           p.x() >= box.max().x() || p.y() >= box.max().y();
    if (on_border && !in_place[size_t(v)]) m.quad = false;
  }
  // The triangles that move first; those in place after them, drawn only in the wireframe.
  const auto moves = [&](Eigen::Index f) {
    return !m.quad || !in_place[size_t(mesh.F(f, 0))] || !in_place[size_t(mesh.F(f, 1))] ||
           !in_place[size_t(mesh.F(f, 2))];
  };
  std::vector<unsigned> indices;
  indices.reserve(size_t(mesh.F.rows()) * 3);
  m.moved.setEmpty();
  for (const bool moving : {true, false}) {
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      if (moves(f) != moving) continue;
      for (int k = 0; k < 3; ++k) {
        indices.push_back(unsigned(mesh.F(f, k)));
        if (moving) m.moved.extend(mesh.screen.row(mesh.F(f, k)).transpose());
      }
    }
    if (moving) m.moved_count = int(indices.size());
  }
  // The quad: screen = source at the box's corners, as a strip.
  const float x0 = float(box.min().x()), y0 = float(box.min().y()), x1 = float(box.max().x()),
              y1 = float(box.max().y());
  const float quad[16] = {x0, y0, x0, y0, x1, y0, x1, y0, x0, y1, x0, y1, x1, y1, x1, y1};
  glBindBuffer(GL_ARRAY_BUFFER, m.quad_vbo);
  glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STREAM_DRAW);
  glBindVertexArray(m.vao);
  glBindBuffer(GL_ARRAY_BUFFER, m.vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(float)), vertices.data(),
               GL_STREAM_DRAW);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(unsigned)),
               indices.data(), GL_STREAM_DRAW);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  m.index_count = int(indices.size());
  ++m.version;
}

void WarpRenderer::set_heat(int pane, const WarpMesh& mesh,
                            const std::vector<std::array<uint8_t, 3>>& colours) {
  if (colours.size() != size_t(mesh.F.rows()))
    throw std::invalid_argument("WarpRenderer::set_heat: " + std::to_string(colours.size()) +
                                " colours for " + std::to_string(mesh.F.rows()) + " triangles");
  // Per corner: screen x, y, source x, y as floats, then the colour's 3 bytes and one unused.
  struct Corner {
    float screen[2], source[2];
    uint8_t colour[4];
  };
  static_assert(sizeof(Corner) == 4 * sizeof(float) + 4);
  std::vector<Corner> corners(size_t(mesh.F.rows()) * 3);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Index v = mesh.F(f, k);
      const std::array<uint8_t, 3>& c = colours[size_t(f)];
      corners[size_t(f) * 3 + size_t(k)] = {{float(mesh.screen(v, 0)), float(mesh.screen(v, 1))},
                                            {float(mesh.source(v, 0)), float(mesh.source(v, 1))},
                                            {c[0], c[1], c[2], 255}};
    }
  Mesh& m = panes_.at(size_t(pane));
  glBindBuffer(GL_ARRAY_BUFFER, m.heat_vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(corners.size() * sizeof(Corner)), corners.data(),
               GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  m.heat_count = int(corners.size());
  ++m.heat_version;
}

void WarpRenderer::clear(int width, int height) const {
  glViewport(0, 0, width, height);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(kBackground[0], kBackground[1], kBackground[2], kBackground[3]);
  glClear(GL_COLOR_BUFFER_BIT);
}

WarpRenderer::Rect WarpRenderer::area(const DrawSettings& s, const Mesh& m) const {
  const Rect pane = s.clip_width > 0 ? Rect{s.clip_x, 0, s.clip_width, s.window_height}
                                     : Rect{0, 0, s.window_width, s.window_height};
  return intersection(intersection(window_rect(s, m.extent, 1), pane),
                      {0, 0, s.window_width, s.window_height});
}

std::optional<WarpRenderer::Rect> WarpRenderer::changing(const DrawSettings& s,
                                                         const Mesh& m) const {
  if (!m.quad || !opaque_) return std::nullopt;
  // The triangles cover no pixel beyond their vertices' box; a ring where the picture is in
  // place lies within about two and a half window pixels of its circle (kFragmentShader).
  Rect r = window_rect(s, m.moved, 1);
  for (const Eigen::Vector3d& c : s.outlines)
    r = united(
        r,
        window_rect(
            s, Eigen::AlignedBox2d(c.head<2>().array() - c.z(), c.head<2>().array() + c.z()), 4));
  return r;
}

bool WarpRenderer::reserve(Cache& c, int width, int height) {
  if (c.framebuffer != 0 && width == c.width && height == c.height) return true;
  c.width = width;
  c.height = height;
  c.valid = false;
  if (c.texture == 0) glGenTextures(1, &c.texture);
  glBindTexture(GL_TEXTURE_2D, c.texture);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  if (c.depth == 0) glGenRenderbuffers(1, &c.depth);
  glBindRenderbuffer(GL_RENDERBUFFER, c.depth);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  if (c.framebuffer == 0) glGenFramebuffers(1, &c.framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, c.framebuffer);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, c.texture, 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, c.depth);
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return complete;
}

void WarpRenderer::redraw(const DrawSettings& s, const Mesh& m, Cache& c, const Rect& dirty) {
  // The texture is the window's size, texel for pixel, its rows top down: Mesa keeps the
  // window's that way and flips y as it draws there, so drawn flipped the picture rasterizes
  // in the texture exactly as in the window (a viewport moved to the picture's area alone, or
  // rows bottom up, round vertices differently: a few pixels on edges would differ).
  glBindFramebuffer(GL_FRAMEBUFFER, c.framebuffer);
  glViewport(0, 0, s.window_width, s.window_height);
  glEnable(GL_SCISSOR_TEST);
  glScissor(dirty.x, dirty.y, dirty.width, dirty.height);
  glClearColor(kBackground[0], kBackground[1], kBackground[2], kBackground[3]);
  glClear(GL_COLOR_BUFFER_BIT);
  paint(s, m, -1);
  glDisable(GL_SCISSOR_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void WarpRenderer::draw(const DrawSettings& s) {
  const Mesh& m = panes_.at(size_t(s.pane));
  if (m.index_count == 0) return;
  Cache& c = caches_.at(size_t(s.pane));
  const Rect at = area(s, m);
  if (!caching_ || at.empty() || !reserve(c, s.window_width, s.window_height)) {
    glViewport(0, 0, s.window_width, s.window_height);
    if (s.clip_width > 0) {
      glEnable(GL_SCISSOR_TEST);
      glScissor(s.clip_x, 0, s.clip_width, s.window_height);
    }
    paint(s, m, 1);
    glDisable(GL_SCISSOR_TEST);
    return;
  }
  const std::optional<Rect> next = changing(s, m);
  const bool same_warp = m.version == c.mesh_version && same_outlines(s, c.settings);
  if (!c.valid || !(at == c.area) || !same_view(s, c.settings) ||
      c.image_version != image_version_ || (s.heatmap && c.heat_version != m.heat_version) ||
      (s.detail && c.detail_version != detail_version_) ||
      (!same_warp && (s.heatmap || s.wireframe || !next || !c.changing))) {
    c.area = at;
    redraw(s, m, c, at);
    ++counts_.full;
  } else if (!same_warp) {
    // The old and the new warp and outlines differ only where either moves or outlines.
    const Rect dirty = intersection(united(*c.changing, *next), at);
    if (!dirty.empty()) redraw(s, m, c, dirty);
    ++counts_.partial;
  } else {
    ++counts_.reused;
  }
  c.valid = true;
  c.settings = s;
  c.mesh_version = m.version;
  c.heat_version = m.heat_version;
  c.image_version = image_version_;
  c.detail_version = detail_version_;
  c.changing = next;
  // Copied into the window, pixel for pixel (the scissor would clip it: off).
  const int bottom = s.window_height - at.y - at.height;
  glDisable(GL_SCISSOR_TEST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, c.framebuffer);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glBlitFramebuffer(at.x, at.y, at.x + at.width, at.y + at.height, at.x, bottom + at.height,
                    at.x + at.width, bottom, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void WarpRenderer::paint(const DrawSettings& s, const Mesh& m, float flip) const {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  // An opaque picture covers what is below it: no blending (a third of llvmpipe's fill).
  if (opaque_) {
    glDisable(GL_BLEND);
  } else {
    glEnable(GL_BLEND);
  }
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glUseProgram(program_);
  glUniform2f(loc_origin_, float(s.origin.x()), float(s.origin.y()));
  glUniform1f(loc_scale_, float(s.scale));
  glUniform2f(loc_window_, float(s.window_width), float(s.window_height));
  glUniform1f(loc_flip_, flip);
  glUniform1f(loc_depth_, 0.0f);
  // The texture's extent in source pixels: its level's texels are 2^level source pixels each
  // (a level's sides round up, so it may reach past the image).
  glUniform2f(loc_size_, float(texture_width_ << texture_level_),
              float(texture_height_ << texture_level_));
  std::vector<float> circles;
  for (const Eigen::Vector3d& c : s.outlines)
    if (circles.size() < 3 * kMaxOutlines)
      circles.insert(circles.end(), {float(c.x()), float(c.y()), float(c.z())});
  glUniform1i(loc_count_, GLint(circles.size() / 3));
  if (!circles.empty()) glUniform3fv(loc_circles_, GLsizei(circles.size() / 3), circles.data());
  glUniform1i(loc_selected_, s.selected);
  glUniform1i(loc_flat_, 0);
  glUniform1i(loc_detail_, s.detail && !detail_area_.empty() ? 1 : 0);
  glUniform4f(loc_detail_area_, float(detail_area_.x), float(detail_area_.y),
              float(detail_area_.width), float(detail_area_.height));
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, detail_texture_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  if (s.heatmap && m.heat_count > 0) {
    glUniform1f(loc_heat_, float(s.heat_opacity));
    glBindVertexArray(m.heat_vao);
    glDrawArrays(GL_TRIANGLES, 0, m.heat_count);
  } else {
    glUniform1f(loc_heat_, 0.0f);
    glBindVertexArray(m.vao);
    if (m.quad && opaque_) {
      // The moving triangles first, then the quad behind them where they left the depth clear:
      // each pixel shaded once (drawn over the quad, the triangles' area was shaded twice).
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      glClear(GL_DEPTH_BUFFER_BIT);
      glDrawElements(GL_TRIANGLES, m.moved_count, GL_UNSIGNED_INT, nullptr);
      glUniform1f(loc_depth_, 0.5f);
      glBindVertexArray(m.quad_vao);
      glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
      glUniform1f(loc_depth_, 0.0f);
      glDisable(GL_DEPTH_TEST);
    } else {
      glDrawElements(GL_TRIANGLES, m.index_count, GL_UNSIGNED_INT, nullptr);
    }
  }
  if (s.wireframe) {
    glEnable(GL_BLEND);
    glBindVertexArray(m.vao);
    glUniform1i(loc_flat_, 1);
    glUniform4f(loc_colour_, 0.1f, 0.9f, 0.9f, 0.45f);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glDrawElements(GL_TRIANGLES, m.index_count, GL_UNSIGNED_INT, nullptr);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
  glBindVertexArray(0);
  glDisable(GL_BLEND);
}

}  // namespace geolens::view
