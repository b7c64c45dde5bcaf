#pragma once
// A WarpMesh drawn on the GPU: its screen positions as vertices, its source positions over the
// image size as texture coordinates, sampling a mipmapped texture of the image with trilinear
// filtering. The circle lenses' outlines are drawn where the warp shows them, in the fragment
// shader (a ring at the circle's radius in source pixels, one screen pixel wide). The heatmap
// overlay draws each triangle in a colour given per triangle (three vertices of its own, so the
// colour does not blend across edges) over the grey of the picture. Two meshes can be held, one
// per pane of a split view, drawn with the same texture.
//
// What costs under a software OpenGL (Mesa's llvmpipe sets up every triangle on the CPU) is kept
// off most frames two ways. The part of a warp that leaves the image in place (the identity,
// which a focus lens's finite footprint leaves beyond it) is drawn as one textured quad and only
// the triangles that move over it. And each pane's picture is drawn into a texture of its own
// (an offscreen framebuffer the window's size), drawn again only where something changed, and
// its area copied to the window every frame: a frame with nothing new costs one copy, and a new
// warp of the same view redraws only the box of what its lenses moved.
//
// A source finer than its frame (a vector map, an SVG) can be shown with its own detail: a picture
// of the warp rendered on the CPU at the resolution of the window (set_detail) is then what the
// triangles show, sampled at their window position instead of the image at their source position,
// so the outlines, wireframe and heatmap are drawn over it as over the image.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "geolens/io/image.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens::view {

/// How a frame is drawn: where the warp's screen frame lands in the window, and the overlays.
struct DrawSettings {
  int window_width = 0, window_height = 0;  ///< framebuffer, pixels
  /// Window pixel of the warp's screen point s: origin + s * scale.
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double scale = 1;
  /// The window columns [clip_x, clip_x + clip_width) drawn into; clip_width 0: all of them.
  int clip_x = 0, clip_width = 0;
  int pane = 0;  ///< the mesh drawn, 0 or 1
  bool wireframe = false;
  /// The pane's heatmap (set_heat) instead of the picture: per triangle opacity x its colour +
  /// (1 - opacity) x the picture's luminance, as heatmap() (annotate.h) blends it.
  bool heatmap = false;
  double heat_opacity = 0.75;
  /// Circles to outline: (centre x, centre y, radius), source pixels; at most kMaxOutlines.
  std::vector<Eigen::Vector3d> outlines;
  int selected = -1;  ///< the outline drawn in the selection colour, -1: none
  /// The picture of set_detail instead of the image: it must be of this pane's warp and view.
  bool detail = false;
};

/// What draw() did with the panes' cached pictures since the renderer was made.
struct CacheCounts {
  int full = 0;     ///< pictures drawn whole: the first, a new view, overlay or image
  int partial = 0;  ///< redrawn where a new warp or outline differs from the last
  int reused = 0;   ///< copied to the window as they were
};

class WarpRenderer {
 public:
  static constexpr int kMaxOutlines = 32;
  /// The texture's limits besides GL_MAX_TEXTURE_SIZE: a side most GPUs take, and the bytes of
  /// its texels (mipmaps add a third) that leave room for everything else.
  static constexpr int kMaxTextureSide = 8192;
  static constexpr size_t kTextureBytes = size_t(192) << 20;
  static constexpr int kPanes = 2;

  /// Compiles the shaders; needs a current OpenGL 3.3 core context. Throws std::runtime_error
  /// with the compiler's log if they do not build.
  WarpRenderer();
  ~WarpRenderer();
  WarpRenderer(const WarpRenderer&) = delete;
  WarpRenderer& operator=(const WarpRenderer&) = delete;

  /// Uploads `image` (1 - 4 channels) with its mipmaps; an image larger than the GPU's largest
  /// texture, kMaxTextureSide or kTextureBytes is uploaded at the finest level of its pyramid
  /// that fits, made through a TiledSource.
  void set_image(const Image& image);
  /// The level of the image's pyramid uploaded (0: the image), and its size in texels.
  int texture_level() const { return texture_level_; }
  int texture_width() const { return texture_width_; }
  int texture_height() const { return texture_height_; }
  /// Uploads the triangles of `mesh` (source pixels of the image set last) for `pane`. When the
  /// mesh's source covers its bounding box and the vertices on that box's border are in place
  /// (screen == source, the viewer's framing), the triangles whose three vertices are in place
  /// are drawn as one quad over that box and the others over it, unless the image has texels
  /// that are not opaque (the quad would show through them); otherwise every triangle is.
  void set_mesh(int pane, const WarpMesh& mesh);
  /// The pane's triangles, and those of them drawn as triangles (the rest are the quad's).
  int triangles(int pane) const { return panes_.at(size_t(pane)).index_count / 3; }
  int moved_triangles(int pane) const {
    const Mesh& m = panes_.at(size_t(pane));
    return (m.quad && opaque_ ? m.moved_count : m.index_count) / 3;
  }
  /// Uploads the heatmap of `mesh` for `pane`: `colours` one per triangle (#F), RGB.
  void set_heat(int pane, const WarpMesh& mesh, const std::vector<std::array<uint8_t, 3>>& colours);
  /// Clears the window (width x height framebuffer pixels) to the background.
  void clear(int width, int height) const;
  /// Draws the mesh of settings.pane into its columns of the window: from the pane's cached
  /// picture, redrawn first where it is out of date (with caching off, afresh).
  void draw(const DrawSettings& settings);
  /// Caching on (the default) or off: every frame drawn afresh, as a measure of the cost.
  void set_caching(bool on) { caching_ = on; }
  const CacheCounts& cache_counts() const { return counts_; }

  /// Window pixels, origin top-left, y down: [x, x + width) x [y, y + height).
  struct Rect {
    int x = 0, y = 0, width = 0, height = 0;
    bool empty() const { return width <= 0 || height <= 0; }
    bool operator==(const Rect& o) const {
      return x == o.x && y == o.y && width == o.width && height == o.height;
    }
  };
  /// Uploads `picture` (1 - 4 channels), a pane's warp as shown, to cover window pixels `at`
  /// (stretched if it has fewer texels): what DrawSettings::detail draws.
  void set_detail(const Image& picture, const Rect& at);

 private:
  // One pane's triangles: indexed for the picture (those that move first, moved_count indices,
  // when the quad draws the rest), three vertices each for the heatmap; the quad over the
  // mesh's source box, and boxes of screen positions (the warp's screen pixels) to draw into.
  struct Mesh {
    unsigned vao = 0, vbo = 0, ebo = 0, heat_vao = 0, heat_vbo = 0, quad_vao = 0, quad_vbo = 0;
    int index_count = 0, moved_count = 0, heat_count = 0;
    bool quad = false;
    Eigen::AlignedBox2d extent;  // every vertex's screen position and the source box
    Eigen::AlignedBox2d moved;   // the screen positions of the triangles that move
    std::uint64_t version = 0, heat_version = 0;
  };
  // One pane's picture as last drawn into its texture (the window's size; the picture covers
  // `area` of it), and what it was drawn from.
  struct Cache {
    unsigned framebuffer = 0, texture = 0, depth = 0;
    int width = 0, height = 0;
    bool valid = false;
    Rect area;
    DrawSettings settings;
    std::uint64_t mesh_version = 0, heat_version = 0, image_version = 0, detail_version = 0;
    std::optional<Rect> changing;  // what a new warp or outline may change; none: all of it
  };

  // Draws the picture of `m` with `s`'s uniforms into the framebuffer and viewport bound, y
  // flipped when `flip` is -1.
  void paint(const DrawSettings& s, const Mesh& m, float flip) const;
  // Where the picture of `m` lies in the window, within the pane's columns.
  Rect area(const DrawSettings& s, const Mesh& m) const;
  // The window pixels a new warp or outline may change: where the mesh's triangles move and
  // around the circles outlined where the picture is in place; none when the quad is not used.
  std::optional<Rect> changing(const DrawSettings& s, const Mesh& m) const;
  // Makes c's texture width x height texels (made anew, its picture dropped, if it was another
  // size); false if the framebuffer cannot be made.
  bool reserve(Cache& c, int width, int height);
  // Draws the picture into c's texture within `dirty` (window pixels).
  void redraw(const DrawSettings& s, const Mesh& m, Cache& c, const Rect& dirty);

  unsigned program_ = 0, texture_ = 0, detail_texture_ = 0;
  Rect detail_area_;
  std::uint64_t detail_version_ = 0;
  std::array<Mesh, kPanes> panes_;
  std::array<Cache, kPanes> caches_;
  bool caching_ = true;
  bool opaque_ = true;  // every texel's alpha is 1
  CacheCounts counts_;
  std::uint64_t image_version_ = 0;
  int texture_level_ = 0, texture_width_ = 1, texture_height_ = 1;
  int loc_origin_ = -1, loc_scale_ = -1, loc_window_ = -1, loc_size_ = -1, loc_flat_ = -1,
      loc_colour_ = -1, loc_count_ = -1, loc_circles_ = -1, loc_selected_ = -1, loc_heat_ = -1,
      loc_flip_ = -1, loc_depth_ = -1, loc_detail_ = -1, loc_detail_area_ = -1;
};

}  // namespace geolens::view
