#include "render3d/volume_renderer.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/thread_pool.h"
#include "geolens/core/errors.h"

namespace geolens {

namespace {

constexpr int kTableSize = 4096;
constexpr int kBlock = 8;  ///< voxels per side of the blocks of empty-space skipping

}  // namespace

VolumeRenderer::VolumeRenderer(ScalarVolume volume, TransferFunction transfer,
                               const OrbitCamera& camera, int frame_width, int frame_height,
                               const VolumeStyle& style)
    : volume_(std::move(volume)), style_(style) {
  const char* f = "VolumeRenderer";
  check_volume(volume_, f, "volume");
  require(style.step > 0 && style.step <= 4, f,
          "step " + std::to_string(style.step) + " is not in (0, 4] voxels");
  require(style.opaque > 0 && style.opaque <= 1, f, "opaque must be in (0, 1]");
  require(style.ambient >= 0 && style.diffuse >= 0 && style.specular >= 0 && style.shininess > 0 &&
              style.light.allFinite() && style.light.norm() > 0,
          f, "the lighting is negative or the light direction is zero");
  const Eigen::Vector3d n(volume_.nx, volume_.ny, volume_.nz);
  box_low_ = -0.5 * volume_.spacing;
  box_high_ = (n.array() - 0.5).matrix().cwiseProduct(volume_.spacing);
  const Eigen::Vector3d centre = (box_low_ + box_high_) / 2;
  projection_ =
      place_camera(camera, centre, (box_high_ - box_low_).norm() / 2, frame_width, frame_height);
  light_ = (projection_.rotation.transpose() * style.light).normalized();
  const double voxel = volume_.spacing.minCoeff();
  step_ = style.step * voxel;

  const auto [lo, hi] = std::minmax_element(volume_.values.begin(), volume_.values.end());
  table_low_ = *lo;
  const double range = std::max(double(*hi) - double(*lo), 1e-12);
  table_scale_ = (kTableSize - 1) / range;
  // Extinction per voxel of length: tau = -ln(1 - opacity). The running integrals over the
  // value (in table entries) of tau and of tau x colour give each segment between two samples
  // the mean over the values it crosses (pre-integration), so a thin feature of the transfer
  // function is not missed or banded when a segment steps over it.
  point_.resize(kTableSize);
  integral_.assign(kTableSize, {0, 0, 0, 0});
  for (int i = 0; i < kTableSize; ++i) {
    const std::array<double, 4> c = transfer(table_low_ + i / table_scale_);
    const double tau = -std::log(1 - std::min(c[3], 0.999999));
    point_[size_t(i)] = {c[0], c[1], c[2], tau};
    if (i == 0) continue;
    const std::array<double, 4>& a = point_[size_t(i - 1)];
    const std::array<double, 4>& b = point_[size_t(i)];
    for (int k = 0; k < 3; ++k)
      integral_[size_t(i)][size_t(k)] =
          integral_[size_t(i - 1)][size_t(k)] + (a[3] * a[size_t(k)] + b[3] * b[size_t(k)]) / 2;
    integral_[size_t(i)][3] = integral_[size_t(i - 1)][3] + (a[3] + b[3]) / 2;
  }
  // Empty-space skipping: a block of kBlock^3 cells is visible when some table entry within
  // the range of its corner voxels' values (what samples in it interpolate) is not transparent.
  std::vector<int> opaque_before(kTableSize + 1, 0);  // entries with extinction > 0 before i
  for (int i = 0; i < kTableSize; ++i)
    opaque_before[size_t(i + 1)] = opaque_before[size_t(i)] + (point_[size_t(i)][3] > 0);
  const int n_voxels[3] = {volume_.nx, volume_.ny, volume_.nz};
  for (int a = 0; a < 3; ++a) blocks_[a] = std::max(1, (n_voxels[a] - 2) / kBlock + 1);
  visible_.assign(size_t(blocks_[0]) * size_t(blocks_[1]) * size_t(blocks_[2]), 0);
  for (int bk = 0; bk < blocks_[2]; ++bk)
    for (int bj = 0; bj < blocks_[1]; ++bj)
      for (int bi = 0; bi < blocks_[0]; ++bi) {
        float low = INFINITY, high = -INFINITY;
        for (int k = bk * kBlock; k <= std::min((bk + 1) * kBlock, volume_.nz - 1); ++k)
          for (int j = bj * kBlock; j <= std::min((bj + 1) * kBlock, volume_.ny - 1); ++j)
            for (int i = bi * kBlock; i <= std::min((bi + 1) * kBlock, volume_.nx - 1); ++i) {
              low = std::min(low, volume_.at(i, j, k));
              high = std::max(high, volume_.at(i, j, k));
            }
        const int first =
            std::clamp(int(std::floor((low - table_low_) * table_scale_)), 0, kTableSize - 1);
        const int last =
            std::clamp(int(std::ceil((high - table_low_) * table_scale_)), 0, kTableSize - 1);
        visible_[size_t(bi) + size_t(blocks_[0]) * (size_t(bj) + size_t(blocks_[1]) * size_t(bk))] =
            opaque_before[size_t(last + 1)] > opaque_before[size_t(first)];
      }
}

double VolumeRenderer::value(double u, double v, double w) const {
  const int nx = volume_.nx, ny = volume_.ny, nz = volume_.nz;
  u = std::clamp(u, 0.0, double(nx - 1));
  v = std::clamp(v, 0.0, double(ny - 1));
  w = std::clamp(w, 0.0, double(nz - 1));
  const int i = std::min(int(u), std::max(nx - 2, 0)), j = std::min(int(v), std::max(ny - 2, 0)),
            k = std::min(int(w), std::max(nz - 2, 0));
  const int i1 = std::min(i + 1, nx - 1), j1 = std::min(j + 1, ny - 1),
            k1 = std::min(k + 1, nz - 1);
  const double fu = u - i, fv = v - j, fw = w - k;
  const double c00 = volume_.at(i, j, k) + fu * (volume_.at(i1, j, k) - volume_.at(i, j, k));
  const double c10 = volume_.at(i, j1, k) + fu * (volume_.at(i1, j1, k) - volume_.at(i, j1, k));
  const double c01 = volume_.at(i, j, k1) + fu * (volume_.at(i1, j, k1) - volume_.at(i, j, k1));
  const double c11 = volume_.at(i, j1, k1) + fu * (volume_.at(i1, j1, k1) - volume_.at(i, j1, k1));
  const double c0 = c00 + fv * (c10 - c00), c1 = c01 + fv * (c11 - c01);
  return c0 + fw * (c1 - c0);
}

std::array<double, 4> VolumeRenderer::lookup(const std::vector<std::array<double, 4>>& table,
                                             double position) {
  position = std::clamp(position, 0.0, double(kTableSize - 1));
  const int i = std::min(int(position), kTableSize - 2);
  const double t = position - i;
  std::array<double, 4> out;
  for (int k = 0; k < 4; ++k)
    out[size_t(k)] = table[size_t(i)][size_t(k)] +
                     t * (table[size_t(i + 1)][size_t(k)] - table[size_t(i)][size_t(k)]);
  return out;
}

std::array<double, 4> VolumeRenderer::sample(double u, double v, double w, double& previous,
                                             const Eigen::Vector3d& view) const {
  const double here = (value(u, v, w) - table_low_) * table_scale_;
  const double before = std::isnan(previous) ? here : previous;
  previous = here;
  // The segment's mean extinction and colour over the values from `before` to `here`.
  std::array<double, 4> out = lookup(point_, here);
  const double span = std::clamp(here, 0.0, double(kTableSize - 1)) -
                      std::clamp(before, 0.0, double(kTableSize - 1));
  if (std::abs(span) > 1e-3) {
    const std::array<double, 4> a = lookup(integral_, before), b = lookup(integral_, here);
    out[3] = (b[3] - a[3]) / span;
    if (std::abs(b[3] - a[3]) > 1e-12)
      for (int k = 0; k < 3; ++k) out[size_t(k)] = (b[size_t(k)] - a[size_t(k)]) / (b[3] - a[3]);
  }
  out[3] = 1 - std::exp(-std::max(out[3], 0.0) * style_.step);
  for (int k = 0; k < 3; ++k) out[size_t(k)] = std::clamp(out[size_t(k)], 0.0, 1.0);
  if (!style_.shading || out[3] <= 0) return out;
  // The gradient by central differences one voxel apart, per model unit: smooth across cells.
  const Eigen::Vector3d gradient(
      (value(u + 1, v, w) - value(u - 1, v, w)) / (2 * volume_.spacing.x()),
      (value(u, v + 1, w) - value(u, v - 1, w)) / (2 * volume_.spacing.y()),
      (value(u, v, w + 1) - value(u, v, w - 1)) / (2 * volume_.spacing.z()));
  const double length = gradient.norm();
  if (!(length > 1e-12)) return out;
  Eigen::Vector3d normal = -gradient / length;
  if (normal.dot(view) < 0) normal = -normal;
  const double ndl = std::max(0.0, normal.dot(light_));
  double highlight = 0;
  if (ndl > 0 && style_.specular > 0)
    highlight = style_.specular *
                std::pow(std::max(0.0, normal.dot((light_ + view).normalized())), style_.shininess);
  const double lit = style_.ambient + style_.diffuse * ndl;
  for (int c = 0; c < 3; ++c) out[size_t(c)] = std::min(1.0, out[size_t(c)] * lit + highlight);
  return out;
}

Image VolumeRenderer::render(const PixelRegion& region, ThreadPool* pool) const {
  check_region(region, "VolumeRenderer::render");
  Image out(region.width, region.height, 3);
  constexpr int band = 8;
  const int bands = (region.height + band - 1) / band;
  auto task = [&](size_t b) {
    const int first = int(b) * band;
    render_rows(region, out, first, std::min(band, region.height - first));
  };
  if (pool != nullptr && bands > 1)
    pool->run(size_t(bands), task);
  else
    for (int b = 0; b < bands; ++b) task(size_t(b));
  return out;
}

void VolumeRenderer::render_rows(const PixelRegion& region, Image& out, int first_row,
                                 int rows) const {
  const Eigen::Vector3d inverse_spacing = volume_.spacing.cwiseInverse();
  for (int row = first_row; row < first_row + rows; ++row) {
    const double y = (double(region.y + row) + 0.5) * region.pixel_size;
    uint8_t* pixel = out.at(0, row);
    for (int i = 0; i < region.width; ++i, pixel += 3) {
      const double x = (double(region.x + i) + 0.5) * region.pixel_size;
      const Eigen::Vector3d direction = projection_.ray(x, y);
      const Eigen::Vector3d& eye = projection_.eye;
      // The ray's interval inside the box (slabs).
      double t0 = 0, t1 = INFINITY;
      for (int a = 0; a < 3; ++a) {
        const double d = direction[a];
        if (d == 0) {
          if (eye[a] < box_low_[a] || eye[a] > box_high_[a]) t1 = -1;
          continue;
        }
        double near = (box_low_[a] - eye[a]) / d, far = (box_high_[a] - eye[a]) / d;
        if (near > far) std::swap(near, far);
        t0 = std::max(t0, near);
        t1 = std::min(t1, far);
      }
      double colour[3] = {0, 0, 0}, alpha = 0;
      const Eigen::Vector3d view = -direction;
      double previous = NAN;  // the table position of the previous sample
      const Eigen::Vector3d origin = eye.cwiseProduct(inverse_spacing);
      const Eigen::Vector3d heading = direction.cwiseProduct(inverse_spacing);  // voxels per t
      for (long long m = 0; alpha < style_.opaque; ++m) {
        const double t = t0 + (double(m) + 0.5) * step_;
        if (!(t < t1)) break;
        const Eigen::Vector3d p = origin + t * heading;
        const int b[3] = {std::clamp(int(std::floor(p.x() / kBlock)), 0, blocks_[0] - 1),
                          std::clamp(int(std::floor(p.y() / kBlock)), 0, blocks_[1] - 1),
                          std::clamp(int(std::floor(p.z() / kBlock)), 0, blocks_[2] - 1)};
        if (!visible_[size_t(b[0]) +
                      size_t(blocks_[0]) * (size_t(b[1]) + size_t(blocks_[1]) * size_t(b[2]))]) {
          // A block every value of which is transparent: go on from the first sample past it.
          double exit = INFINITY;
          for (int a = 0; a < 3; ++a) {
            if (heading[a] > 0 && b[a] < blocks_[a] - 1)
              exit = std::min(exit, ((b[a] + 1) * kBlock - origin[a]) / heading[a]);
            else if (heading[a] < 0 && b[a] > 0)
              exit = std::min(exit, (b[a] * kBlock - origin[a]) / heading[a]);
          }
          if (!(exit < t1)) break;
          m = std::max(m, (long long)(std::ceil((exit - t0) / step_ - 0.5)) - 1);
          previous = NAN;
          continue;
        }
        const std::array<double, 4> s = sample(p.x(), p.y(), p.z(), previous, view);
        if (s[3] <= 0) continue;
        const double weight = (1 - alpha) * s[3];
        for (int c = 0; c < 3; ++c) colour[c] += weight * s[size_t(c)];
        alpha += weight;
      }
      for (int c = 0; c < 3; ++c) {
        const double v = 255 * colour[c] + (1 - alpha) * style_.background[size_t(c)];
        pixel[c] = uint8_t(std::clamp(std::lround(v), 0L, 255L));
      }
    }
  }
}

}  // namespace geolens
