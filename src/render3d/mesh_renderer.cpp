#include "render3d/mesh_renderer.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/thread_pool.h"
#include "geolens/core/errors.h"

namespace geolens {

namespace {

/// An edge p -> q of a triangle in sample units, evaluated from its lexicographically smaller
/// end whichever way it runs, so the two triangles sharing it compute exactly opposite values.
struct EdgeFunction {
  double px, py, dx, dy, sign;
  bool tie_inside;  ///< whether a sample exactly on the edge counts as inside

  EdgeFunction(const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    const bool forward = p.x() < q.x() || (p.x() == q.x() && p.y() < q.y());
    const Eigen::Vector2d& from = forward ? p : q;
    const Eigen::Vector2d& to = forward ? q : p;
    px = from.x();
    py = from.y();
    dx = to.x() - from.x();
    dy = to.y() - from.y();
    sign = forward ? 1 : -1;
    const double ex = q.x() - p.x(), ey = q.y() - p.y();
    tie_inside = ey > 0 || (ey == 0 && ex < 0);
  }
  double operator()(double x, double y) const { return sign * (dx * (y - py) - dy * (x - px)); }
  bool inside(double value) const { return value > 0 || (value == 0 && tie_inside); }
  double length() const { return std::hypot(dx, dy); }
};

/// Triangle f in sample units, its corners ordered so that its signed area is positive.
struct SetUp {
  int corner[3];
  Eigen::Vector2d p[3];
  double area2 = 0;  ///< twice the area, sample units^2; 0: skip the triangle
};

/// What a band is drawn from: the renderer's vertices and faces in camera coordinates, its style
/// and light, and the scale of the band's samples.
struct BandScene {
  const Eigen::MatrixXi& faces;
  const std::vector<Eigen::Vector2d>& screen;       ///< per vertex, frame pixels
  const std::vector<double>& inverse_depth;         ///< per vertex, 1 / depth (<= 0: behind)
  const std::vector<Eigen::Vector3d>& position;     ///< per vertex
  const std::vector<Eigen::Vector3d>& normal;       ///< per vertex
  const std::vector<Eigen::Vector3d>& face_normal;  ///< per face
  const MeshStyle& style;
  const Eigen::Vector3d& light;  ///< unit
  double to_samples;             ///< sample units per frame pixel
};

/// A band's samples, sw x sh from the absolute sample (x0, y0), row-major.
struct BandSamples {
  long long x0, y0;
  int sw, sh;
  std::vector<double> depth;  ///< the nearest triangle's 1 / depth; 0 = nothing
  std::vector<int> face;      ///< the nearest triangle; -1 = none
};

/// Triangle t in sample units; area2 0 if a corner is behind the eye or the area is not finite.
/// Inlined at both its calls (see shade).
inline SetUp set_up(const BandScene& scene, Eigen::Index t) {
  SetUp s;
  for (int k = 0; k < 3; ++k) {
    s.corner[k] = scene.faces(t, k);
    if (scene.inverse_depth[size_t(s.corner[k])] <= 0) return s;
    s.p[k] = scene.screen[size_t(s.corner[k])] * scene.to_samples;
  }
  const EdgeFunction ab(s.p[0], s.p[1]);
  s.area2 = ab(s.p[2].x(), s.p[2].y());
  if (s.area2 < 0) {
    std::swap(s.corner[1], s.corner[2]);
    std::swap(s.p[1], s.p[2]);
    s.area2 = -s.area2;
  }
  if (!std::isfinite(s.area2)) s.area2 = 0;
  return s;
}

/// Makes triangle t (set up as `s`, area2 > 0) the nearest at the band's samples it covers where
/// it is nearer than the one there.
void rasterize(const BandScene& scene, const SetUp& s, int t, BandSamples& band) {
  const long long x0 = band.x0, y0 = band.y0;
  const double lo_x = std::min({s.p[0].x(), s.p[1].x(), s.p[2].x()});
  const double hi_x = std::max({s.p[0].x(), s.p[1].x(), s.p[2].x()});
  const double lo_y = std::min({s.p[0].y(), s.p[1].y(), s.p[2].y()});
  const double hi_y = std::max({s.p[0].y(), s.p[1].y(), s.p[2].y()});
  const long long bx0 = std::max<long long>(x0, (long long)std::ceil(lo_x - 0.5));
  const long long bx1 = std::min<long long>(x0 + band.sw - 1, (long long)std::floor(hi_x - 0.5));
  const long long by0 = std::max<long long>(y0, (long long)std::ceil(lo_y - 0.5));
  const long long by1 = std::min<long long>(y0 + band.sh - 1, (long long)std::floor(hi_y - 0.5));
  if (bx0 > bx1 || by0 > by1) return;
  const EdgeFunction e_bc(s.p[1], s.p[2]), e_ca(s.p[2], s.p[0]), e_ab(s.p[0], s.p[1]);
  const double ia = scene.inverse_depth[size_t(s.corner[0])],
               ib = scene.inverse_depth[size_t(s.corner[1])],
               ic = scene.inverse_depth[size_t(s.corner[2])];
  for (long long Y = by0; Y <= by1; ++Y) {
    const double y = double(Y) + 0.5;
    for (long long X = bx0; X <= bx1; ++X) {
      const double x = double(X) + 0.5;
      const double wa = e_bc(x, y), wb = e_ca(x, y), wc = e_ab(x, y);
      if (!e_bc.inside(wa) || !e_ca.inside(wb) || !e_ab.inside(wc)) continue;
      const double z = (wa * ia + wb * ib + wc * ic) / s.area2;
      const size_t i = size_t(Y - y0) * size_t(band.sw) + size_t(X - x0);
      if (z > band.depth[i]) {
        band.depth[i] = z;
        band.face[i] = t;
      }
    }
  }
}

/// The camera-space point `q` and normal `n` (not normalized) at the point of triangle `s` whose
/// edge functions are `e`, interpolated perspective-correctly from its corners.
void interpolate(const BandScene& scene, const SetUp& s, const double e[3], Eigen::Vector3d& q,
                 Eigen::Vector3d& n) {
  double w[3], total = 0;
  for (int k = 0; k < 3; ++k) {
    w[k] = e[k] / s.area2 * scene.inverse_depth[size_t(s.corner[k])];
    total += w[k];
  }
  q = Eigen::Vector3d::Zero();
  n = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    w[k] /= total;
    q += w[k] * scene.position[size_t(s.corner[k])];
    n += w[k] * scene.normal[size_t(s.corner[k])];
  }
}

/// The colour `rgb` of the sample at (x, y), sample units, that triangle t (set up as `s`)
/// covers: lit by the light and the ambient light (Blinn-Phong, from either side), or the edge
/// colour within half the edge width of an edge. Not inlined, and set_up inlined: GCC 12's
/// choice the other way round made render() 15% slower (a 1024 x 1024 view, 180k triangles).
[[gnu::noinline]] void shade(const BandScene& scene, const SetUp& s, int t, double x, double y,
                             double frame_per_sample, double rgb[3]) {
  const MeshStyle& style = scene.style;
  const EdgeFunction e_bc(s.p[1], s.p[2]), e_ca(s.p[2], s.p[0]), e_ab(s.p[0], s.p[1]);
  const double e[3] = {e_bc(x, y), e_ca(x, y), e_ab(x, y)};
  Eigen::Vector3d q, n;
  interpolate(scene, s, e, q, n);
  if (style.shading == MeshShading::flat || n.norm() < 1e-12) n = scene.face_normal[size_t(t)];
  n.normalize();
  const Eigen::Vector3d view = -q.normalized();
  if (n.dot(view) < 0) n = -n;
  const double ndl = std::max(0.0, n.dot(scene.light));
  double highlight = 0;
  if (ndl > 0 && style.specular > 0) {
    const Eigen::Vector3d h = (scene.light + view).normalized();
    highlight = style.specular * std::pow(std::max(0.0, n.dot(h)), style.shininess);
  }
  const double lit = style.ambient + style.diffuse * ndl;
  bool on_edge = false;
  if (style.edges) {
    const EdgeFunction* edges[3] = {&e_bc, &e_ca, &e_ab};
    for (int k = 0; k < 3; ++k)
      if (std::abs(e[k]) / edges[k]->length() * frame_per_sample < style.edge_width / 2)
        on_edge = true;
  }
  for (int c = 0; c < 3; ++c)
    rgb[c] = on_edge ? double(style.edge_colour[size_t(c)])
                     : std::min(255.0, style.colour[size_t(c)] * lit + 255 * highlight);
}

/// Pixel row `row` of the band: each pixel the mean of its samples, shaded (the background where
/// no triangle is), written to `pixel` (RGB). `sum`: scratch of 3 per pixel.
void shade_row(const BandScene& scene, const BandSamples& band, int row, double frame_per_sample,
               std::vector<double>& sum, uint8_t* pixel) {
  const int ss = scene.style.samples;
  const long long x0 = band.x0, y0 = band.y0;
  std::fill(sum.begin(), sum.end(), 0.0);
  for (int a = 0; a < ss; ++a) {
    const long long Y = y0 + (long long)(row)*ss + a;
    const double y = double(Y) + 0.5;
    for (int sx = 0; sx < band.sw; ++sx) {
      const size_t i = size_t(Y - y0) * size_t(band.sw) + size_t(sx);
      double rgb[3] = {double(scene.style.background[0]), double(scene.style.background[1]),
                       double(scene.style.background[2])};
      if (band.face[i] >= 0) {
        const SetUp s = set_up(scene, band.face[i]);
        const double x = double(x0 + sx) + 0.5;
        shade(scene, s, band.face[i], x, y, frame_per_sample, rgb);
      }
      double* target = &sum[size_t(sx / ss) * 3];
      for (int c = 0; c < 3; ++c) target[c] += rgb[c];
    }
  }
  const double samples = double(ss) * ss;
  for (size_t c = 0; c < sum.size(); ++c)
    pixel[c] = uint8_t(std::clamp(std::lround(sum[c] / samples), 0L, 255L));
}

}  // namespace

MeshRenderer::MeshRenderer(TriangleMesh mesh, const OrbitCamera& camera, int frame_width,
                           int frame_height, const MeshStyle& style)
    : style_(style), frame_width_(frame_width), frame_height_(frame_height) {
  const char* f = "MeshRenderer";
  check_triangle_mesh(mesh, f, "mesh");
  require(style.samples >= 1 && style.samples <= 8, f,
          "samples " + std::to_string(style.samples) + " is not in [1, 8]");
  require(style.ambient >= 0 && style.diffuse >= 0 && style.specular >= 0 && style.shininess > 0 &&
              style.edge_width > 0 && style.light.allFinite() && style.light.norm() > 0,
          f, "the lighting or edge width is negative or the light direction is zero");
  Eigen::Vector3d centre;
  double radius = 0;
  bounding_sphere(mesh, centre, radius);
  projection_ = place_camera(camera, centre, radius, frame_width, frame_height);
  light_ = style.light.normalized();
  if (mesh.N.rows() == 0) mesh.N = vertex_normals(mesh.V, mesh.F);
  const Eigen::MatrixXd face_n = face_normals(mesh.V, mesh.F);
  faces_ = mesh.F;
  const size_t n = size_t(mesh.V.rows());
  screen_.resize(n);
  inverse_depth_.resize(n);
  position_.resize(n);
  normal_.resize(n);
  for (size_t v = 0; v < n; ++v) {
    const Eigen::Vector3d q = projection_.to_camera(mesh.V.row(Eigen::Index(v)).transpose());
    position_[v] = q;
    inverse_depth_[v] = -q.z() > 0 ? 1 / -q.z() : 0;
    screen_[v] = -q.z() > 0 ? projection_.project(q) : Eigen::Vector2d::Zero();
    normal_[v] = projection_.rotation * mesh.N.row(Eigen::Index(v)).transpose();
  }
  face_normal_.resize(size_t(faces_.rows()));
  for (Eigen::Index t = 0; t < faces_.rows(); ++t)
    face_normal_[size_t(t)] = projection_.rotation * face_n.row(t).transpose();
}

Image MeshRenderer::render(const PixelRegion& region, ThreadPool* pool) const {
  check_region(region, "MeshRenderer::render");
  Image out(region.width, region.height, 3);
  constexpr int band = 32;
  const int bands = (region.height + band - 1) / band;
  // The triangles each band may cover, in their order in F (their bounding boxes, a pixel
  // wider, against the band's), so a band or a small tile does not visit the whole mesh.
  std::vector<std::vector<int>> in_band(static_cast<size_t>(bands));
  const double s = region.pixel_size;
  const double left = region.x * s - s, right = (double(region.x) + region.width) * s + s;
  for (Eigen::Index t = 0; t < faces_.rows(); ++t) {
    double lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY, hi_y = -INFINITY;
    bool behind = false;
    for (int k = 0; k < 3; ++k) {
      const size_t v = size_t(faces_(t, k));
      behind = behind || inverse_depth_[v] <= 0;
      lo_x = std::min(lo_x, screen_[v].x());
      hi_x = std::max(hi_x, screen_[v].x());
      lo_y = std::min(lo_y, screen_[v].y());
      hi_y = std::max(hi_y, screen_[v].y());
    }
    if (behind || hi_x < left || lo_x > right) continue;
    const double first_row = std::floor(lo_y / s) - 1 - region.y;
    const double last_row = std::floor(hi_y / s) + 1 - region.y;
    if (last_row < 0 || first_row >= region.height) continue;
    const int b0 = int(std::max(first_row, 0.0)) / band;
    const int b1 = int(std::min(last_row, double(region.height - 1))) / band;
    for (int b = b0; b <= b1; ++b) in_band[size_t(b)].push_back(int(t));
  }
  auto task = [&](size_t b) {
    const int first = int(b) * band;
    render_band(region, out, first, std::min(band, region.height - first), in_band[b]);
  };
  if (pool != nullptr && bands > 1)
    pool->run(size_t(bands), task);
  else
    for (int b = 0; b < bands; ++b) task(size_t(b));
  return out;
}

void MeshRenderer::render_band(const PixelRegion& region, Image& out, int first_row, int rows,
                               const std::vector<int>& triangles) const {
  const int ss = style_.samples;
  const double to_samples = ss / region.pixel_size;  // sample units per frame pixel
  const BandScene scene{faces_,       screen_, inverse_depth_, position_, normal_,
                        face_normal_, style_,  light_,         to_samples};
  BandSamples band;
  band.x0 = (long long)(region.x) * ss;
  band.y0 = (long long)(region.y + first_row) * ss;
  band.sw = region.width * ss;
  band.sh = rows * ss;
  band.depth.assign(size_t(band.sw) * size_t(band.sh), 0);
  band.face.assign(size_t(band.sw) * size_t(band.sh), -1);

  // Visibility: the nearest triangle at each sample.
  for (const int t : triangles) {
    const SetUp s = set_up(scene, t);
    if (s.area2 <= 0) continue;
    rasterize(scene, s, t, band);
  }

  // Shading, then the mean of each pixel's samples.
  const double frame_per_sample = region.pixel_size / ss;
  std::vector<double> sum(size_t(region.width) * 3);
  for (int row = 0; row < rows; ++row)
    shade_row(scene, band, row, frame_per_sample, sum, out.at(0, first_row + row));
}

}  // namespace geolens
