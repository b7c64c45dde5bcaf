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

// The T at `data`, its bytes reversed first when `swap`.
template <typename T>
T load(const unsigned char* data, bool swap) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, data, sizeof(T));
  if (swap) std::reverse(bytes, bytes + sizeof(T));
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

template <typename T>
void decode(const unsigned char* data, size_t count, bool swap, float* out) {
  for (size_t i = 0; i < count; ++i) out[i] = float(load<T>(data + i * sizeof(T), swap));
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

double decode_sample(const unsigned char* data, VoxelType type, bool swap) {
  switch (type) {
    case VoxelType::int8:
      return load<int8_t>(data, swap);
    case VoxelType::uint8:
      return load<uint8_t>(data, swap);
    case VoxelType::int16:
      return load<int16_t>(data, swap);
    case VoxelType::uint16:
      return load<uint16_t>(data, swap);
    case VoxelType::int32:
      return load<int32_t>(data, swap);
    case VoxelType::uint32:
      return load<uint32_t>(data, swap);
    case VoxelType::float32:
      return load<float>(data, swap);
    case VoxelType::float64:
      return load<double>(data, swap);
  }
  return 0;
}

}  // namespace geolens::detail
