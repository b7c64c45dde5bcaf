#pragma once
// The sample types of volume files, decoded to float (private to the volume readers).

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

}  // namespace geolens::detail
