#include "source/volume_source.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>

#include "geolens/core/errors.h"
#include "render3d/nifti_file.h"
#include "render3d/nrrd_file.h"
#include "source/scene_tiles.h"

namespace geolens {

SourceFile volume_source(ScalarVolume volume, TransferFunction transfer, int frame_width,
                         int frame_height, const VolumeSourceOptions& options) {
  auto renderer =
      std::make_shared<const VolumeRenderer>(std::move(volume), std::move(transfer), options.camera,
                                             frame_width, frame_height, options.style);
  return scene_source([renderer](const PixelRegion& region) { return renderer->render(region); },
                      frame_width, frame_height, options.detail_levels, options.tiling, "volume");
}

SourceFile open_volume_source(const std::string& path, const SourceFileOptions& options,
                              const VolumeSourceOptions& volume) {
  const char* f = "open_volume_source";
  std::string name = std::filesystem::path(path).filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  auto ends_with = [&](const std::string& suffix) {
    return name.size() > suffix.size() &&
           name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  const bool nifti = ends_with(".nii") || ends_with(".nii.gz");
  require(nifti || ends_with(".nrrd"), f,
          "'" + path + "' is not a volume file (expected .nii, .nii.gz or .nrrd)");
  require(
      (options.width == 0) == (options.height == 0) && options.width >= 0 && options.height >= 0, f,
      "'" + path + "': size " + std::to_string(options.width) + " x " +
          std::to_string(options.height) + " has an empty side");
  VolumeSourceOptions chosen = volume;
  const size_t max_voxels = options.max_voxels > 0 ? size_t(options.max_voxels) : kMaxVoxels;
  ScalarVolume loaded = nifti ? load_nifti(path, max_voxels) : load_nrrd(path, max_voxels);
  try {
    parse_view(options.view, chosen.camera);
    TransferFunction transfer = transfer_function(options.transfer, loaded);
    const int width = options.width == 0 ? 1024 : options.width;
    const int height = options.height == 0 ? 1024 : options.height;
    return volume_source(std::move(loaded), std::move(transfer), width, height, chosen);
  } catch (const InvalidInput& e) {
    throw InvalidInput(std::string(f) + ": '" + path + "': " + e.what());
  }
}

}  // namespace geolens
