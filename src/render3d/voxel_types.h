#pragma once
// The binary sample types of volume and PLY files, decoded (private to render3d's readers).

#include <cstddef>
#include <cstdint>
#include <string>

namespace geolens::detail {

enum class VoxelType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

int voxel_bytes(VoxelType type);
std::string voxel_type_name(VoxelType type);

/// Decodes `count` samples of `type` at `data` into `out`, swapping each sample's bytes first
/// when `swap`.
void decode_voxels(const unsigned char* data, size_t count, VoxelType type, bool swap, float* out);

/// The one sample of `type` at `data`, its bytes swapped first when `swap`, exactly as a double.
double decode_sample(const unsigned char* data, VoxelType type, bool swap);

}  // namespace geolens::detail
