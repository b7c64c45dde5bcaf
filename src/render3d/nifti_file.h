#pragma once
// NIfTI-1 scalar volumes (.nii, .nii.gz), read with Debian's libnifti (niftiio + znzlib).

#include <string>

#include "render3d/scalar_volume.h"

namespace geolens {

/// Reads the first 3D volume of a NIfTI-1 file (.nii, or gzipped .nii.gz; a 4D file's first
/// time point) of type uint8, int8, int16, uint16, int32, uint32, float32 or float64, its
/// values scaled by scl_slope / scl_inter when the slope is non-zero, its spacing |pixdim[1..3]|
/// (1 where 0). libnifti's own messages to stderr are silenced (its debug level is set to 0 on
/// the first call, for the process) since every refusal is reported here. Thread-safe (calls
/// into libnifti are serialized). Throws InvalidInput naming "load_nifti" and the file: not a
/// NIfTI-1 file, a volume of zero size, an unsupported type, data that ends before the header's
/// voxels (the header claims more data than the file holds), more than `max_voxels` voxels (>= 1;
/// the message names the limit) or bytes of samples than volume_bytes_limit.
ScalarVolume load_nifti(const std::string& path, size_t max_voxels = kMaxVoxels);

}  // namespace geolens
