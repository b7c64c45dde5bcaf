#include "render3d/scalar_volume.h"

#include <cmath>

#include "core/limits.h"
#include "geolens/core/errors.h"

namespace geolens {

void check_volume(const ScalarVolume& volume, const char* function, const std::string& file) {
  const std::string where = "'" + file + "': ";
  const std::string size = std::to_string(volume.nx) + " x " + std::to_string(volume.ny) + " x " +
                           std::to_string(volume.nz);
  require(volume.nx >= 1 && volume.ny >= 1 && volume.nz >= 1, function,
          where + "a volume of zero size (" + size + " voxels)");
  require(volume.values.size() == size_t(volume.nx) * size_t(volume.ny) * size_t(volume.nz),
          function, where + std::to_string(volume.values.size()) + " values for " + size);
  require(volume.spacing.allFinite() && volume.spacing.minCoeff() > 0, function,
          where + "the voxel spacing must be finite and positive");
  for (const float v : volume.values)
    require(std::isfinite(v), function, where + "a voxel value is not finite");
}

std::string voxel_limit_message(uint64_t voxels, size_t max_voxels) {
  return std::to_string(voxels) + " voxels, " + over_limit(max_voxels, "max_voxels");
}

}  // namespace geolens
