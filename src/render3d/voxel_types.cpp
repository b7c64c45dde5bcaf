#include "render3d/voxel_types.h"

#include <algorithm>
#include <cstring>

namespace geolens::detail {

int voxel_bytes(VoxelType type) {
  switch (type) {
    case VoxelType::int8:
    case VoxelType::uint8:
      return 1;
    case VoxelType::int16:
    case VoxelType::uint16:
      return 2;
    case VoxelType::int32:
    case VoxelType::uint32:
    case VoxelType::float32:
      return 4;
    case VoxelType::float64:
      return 8;
  }
  return 1;
}

std::string voxel_type_name(VoxelType type) {
  switch (type) {
    case VoxelType::int8:
      return "int8";
    case VoxelType::uint8:
      return "uint8";
    case VoxelType::int16:
      return "int16";
    case VoxelType::uint16:
      return "uint16";
    case VoxelType::int32:
      return "int32";
    case VoxelType::uint32:
      return "uint32";
    case VoxelType::float32:
      return "float";
    case VoxelType::float64:
      return "double";
  }
  return "?";
}

namespace {

template <typename T>
void decode(const unsigned char* data, size_t count, bool swap, float* out) {
  unsigned char bytes[sizeof(T)];
  for (size_t i = 0; i < count; ++i) {
    std::memcpy(bytes, data + i * sizeof(T), sizeof(T));
    if (swap) std::reverse(bytes, bytes + sizeof(T));
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    out[i] = float(value);
  }
}

}  // namespace

void decode_voxels(const unsigned char* data, size_t count, VoxelType type, bool swap, float* out) {
  switch (type) {
    case VoxelType::int8:
      return decode<int8_t>(data, count, swap, out);
    case VoxelType::uint8:
      return decode<uint8_t>(data, count, swap, out);
    case VoxelType::int16:
      return decode<int16_t>(data, count, swap, out);
    case VoxelType::uint16:
      return decode<uint16_t>(data, count, swap, out);
    case VoxelType::int32:
      return decode<int32_t>(data, count, swap, out);
    case VoxelType::uint32:
      return decode<uint32_t>(data, count, swap, out);
    case VoxelType::float32:
      return decode<float>(data, count, swap, out);
    case VoxelType::float64:
      return decode<double>(data, count, swap, out);
  }
}

}  // namespace geolens::detail
