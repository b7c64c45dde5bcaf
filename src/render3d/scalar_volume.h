#pragma once
// A scalar volume (a CT or MRI scan, a phantom): voxel values on a regular 3D grid.

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace geolens {

/// nx x ny x nz voxels, x fastest: the value of voxel (i, j, k) is values[i + nx (j + ny k)],
/// in the file's physical units (after its scaling: Hounsfield units for a CT). Voxel (i, j, k)
/// has its centre at model point (i sx, j sy, k sz), spacing (sx, sy, sz) in model units (mm
/// for a scan), so the volume fills the box [-s/2, (n - 1/2) s] along each axis.
struct ScalarVolume {
  int nx = 0, ny = 0, nz = 0;
  Eigen::Vector3d spacing{1, 1, 1};  ///< > 0, model units
  std::vector<float> values;         ///< nx ny nz values

  float at(int i, int j, int k) const {
    return values[size_t(i) + size_t(nx) * (size_t(j) + size_t(ny) * size_t(k))];
  }
};

/// The most voxels a volume file is read with (2^28: 1 GiB of values, a 512 x 512 x 1024 scan),
/// checked from its header before anything is allocated (a 110-byte gzipped NRRD claiming 10^10
/// voxels took 9.6 GB).
inline constexpr size_t kMaxVoxels = size_t(1) << 28;
/// The most bytes of samples a volume file is read with (2^30: 2^27 float64 voxels).
inline constexpr size_t kMaxVolumeBytes = size_t(1) << 30;

/// The most bytes of samples read with a limit of `max_voxels`: kMaxVolumeBytes, or 4 a voxel
/// where the limit is raised beyond kMaxVoxels.
inline size_t volume_bytes_limit(size_t max_voxels) {
  return std::max(kMaxVolumeBytes, std::min(max_voxels, size_t(1) << 40) * 4);
}

/// What a reader says of a volume of `voxels` over `max_voxels`, naming the limit.
std::string voxel_limit_message(uint64_t voxels, size_t max_voxels);

/// Throws InvalidInput naming `function` and `file` for a volume with a side of zero voxels
/// ("a volume of zero size"), a value count that is not nx ny nz, a non-finite value, or a
/// spacing that is not finite and positive.
void check_volume(const ScalarVolume& volume, const char* function, const std::string& file);

}  // namespace geolens
