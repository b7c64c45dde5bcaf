#pragma once
// A software (CPU) ray caster for scalar volumes: any region of the view at any resolution.
//
// Why on the CPU rather than Mesa's offscreen OpenGL: as for meshes (mesh_renderer.h), the
// sources render tile by tile from the render's worker threads, headless, and tiles of a level
// must join exactly; a ray per pixel, computed from the pixel's absolute position in the view,
// does that with no context and no dependency, and gives the same result on every machine.
// Measured (bench/scene3d_bench.cpp): a 1024 x 1024 view of a 256^3 CT phantom in 0.33 - 0.7 s
// on 2 cores (half-voxel steps, shaded, empty blocks skipped).

#include <array>
#include <cstdint>
#include <vector>

#include "geolens/io/image.h"
#include "geolens/render3d/camera.h"
#include "render3d/scalar_volume.h"
#include "render3d/transfer_function.h"

namespace geolens {

class ThreadPool;  // core/thread_pool.h

/// How rays are cast and composited.
struct VolumeStyle {
  double step =
      0.5;  ///< distance between samples along a ray, voxels (smallest spacing), in (0, 4]
  /// Shade each sample by the gradient of the volume (central differences one voxel apart; its
  /// normal: towards lower values, lit from both sides) with one directional light, so iso-surfaces
  /// show their shape; false: the transfer function's colour alone (emission-absorption).
  bool shading = true;
  Eigen::Vector3d light{-0.4, 0.6, 0.7};  ///< towards the light, camera coordinates; non-zero
  double ambient = 0.3, diffuse = 0.7, specular = 0.25;  ///< >= 0
  double shininess = 30;                                 ///< > 0
  std::array<uint8_t, 3> background = {0, 0, 0};         ///< RGB behind the volume
  double opaque = 0.98;  ///< a ray stops once its accumulated opacity reaches this, in (0, 1]
};

/// A volume seen by a camera in a frame, ready to render any region of the view. The camera
/// orbits the centre of the volume's box (the bounding sphere of the box). render() is const
/// and thread-safe.
class VolumeRenderer {
 public:
  /// Throws InvalidInput naming "VolumeRenderer" for an invalid volume (check_volume), camera,
  /// frame or style.
  VolumeRenderer(ScalarVolume volume, TransferFunction transfer, const OrbitCamera& camera,
                 int frame_width, int frame_height, const VolumeStyle& style = {});

  /// The RGB pixels of `region`. Each pixel casts one ray through its centre's frame point
  /// (from its absolute grid position, so regions of one grid agree) across the volume's box,
  /// samples it every style.step voxels with trilinear interpolation (clamped to the edge
  /// voxels), maps each segment between samples through the transfer function pre-integrated
  /// over the values it crosses (the mean extinction and colour; Engel, Kraus and Ertl,
  /// "High-quality pre-integrated volume rendering", 2001; opacity for the step's length),
  /// shades it, and composites front to back until the ray is style.opaque. Samples in blocks of
  /// 8^3 voxels whose values are all transparent are skipped (the segment after a skip starts
  /// afresh). `pool`: split the
  /// rows over its threads. Throws InvalidInput naming "VolumeRenderer::render" for an invalid
  /// region.
  Image render(const PixelRegion& region, ThreadPool* pool = nullptr) const;

  const Projection& projection() const { return projection_; }
  const ScalarVolume& volume() const { return volume_; }

 private:
  void render_rows(const PixelRegion& region, Image& out, int first_row, int rows) const;
  /// The trilinear interpolation at voxel coordinates (u, v, w), clamped to the edge voxels.
  double value(double u, double v, double w) const;
  /// RGB and opacity of the ray's segment ending at voxel coordinates (u, v, w), opacity for
  /// one step: pre-integrated over the values from `previous` (the last sample's table position,
  /// NaN at the first; updated) to this sample's.
  std::array<double, 4> sample(double u, double v, double w, double& previous,
                               const Eigen::Vector3d& view) const;
  /// `table` linearly interpolated at a position in entries, clamped to its ends.
  static std::array<double, 4> lookup(const std::vector<std::array<double, 4>>& table,
                                      double position);

  ScalarVolume volume_;
  VolumeStyle style_;
  Projection projection_;
  Eigen::Vector3d light_;               ///< model coordinates, unit
  Eigen::Vector3d box_low_, box_high_;  ///< model coordinates
  double step_ = 1;                     ///< model units
  /// The transfer function tabulated over the volume's values, table position p at value
  /// table_low_ + p / table_scale_: RGB and extinction per voxel of length, and their running
  /// integrals over p (RGB x extinction, extinction).
  std::vector<std::array<double, 4>> point_, integral_;
  /// Per block of 8^3 cells (x fastest), whether any value its samples can take is visible; a
  /// ray skips the samples in a block that is not.
  std::vector<uint8_t> visible_;
  int blocks_[3] = {1, 1, 1};
  double table_low_ = 0, table_scale_ = 1;
};

}  // namespace geolens
