#pragma once
// A scalar volume (NIfTI, NRRD) as a source: the view of a camera, ray cast per tile and level
// of detail, so a magnified focus is a real render at its zoom.

#include <string>

#include "geolens/source/source.h"
#include "geolens/source/source_file.h"
#include "render3d/volume_renderer.h"

namespace geolens {

struct VolumeSourceOptions {
  /// Default: azimuth 30, elevation 20, fitted, 30 degrees; the volume's third axis (k) up and
  /// its second (j) towards the camera at azimuth 0 (for a scan stored in RAS order: head up,
  /// seen from the front).
  OrbitCamera camera = [] {
    OrbitCamera c;
    c.up = {0, 0, 1};
    c.front = {0, 1, 0};
    return c;
  }();
  VolumeStyle style;  ///< default: shaded, half-voxel steps, black background
  /// k: level 0 has 2^k texels per frame pixel (SourceFile::scale), in [0, 4].
  int detail_levels = 2;
  TiledSourceOptions tiling;  ///< tile size and cache budget
};

/// `volume` through `transfer`, seen by options.camera in a frame_width x frame_height frame, as
/// a SourceFile of kind "volume" (source/scene_tiles.h scene_source over a VolumeRenderer).
/// Throws InvalidInput naming "VolumeRenderer" or "scene_source" for an invalid volume, camera,
/// style, frame or tiling.
SourceFile volume_source(ScalarVolume volume, TransferFunction transfer, int frame_width,
                         int frame_height, const VolumeSourceOptions& options = {});

/// Opens a NIfTI (.nii, .nii.gz: load_nifti) or NRRD (.nrrd: load_nrrd) file by its extension
/// as volume_source(): the frame options.width x options.height (0 x 0: 1024 x 1024), the view
/// options.view ("AZ,EL", parse_view), the transfer function options.transfer
/// (transfer_function: "ct", "mri", a table file, or empty for a guess from the values).
/// Throws InvalidInput naming "open_volume_source" and the file for another extension, a frame
/// with one side 0, a bad view or an unknown transfer, and what the readers refuse.
SourceFile open_volume_source(const std::string& path, const SourceFileOptions& options,
                              const VolumeSourceOptions& volume = {});

}  // namespace geolens
