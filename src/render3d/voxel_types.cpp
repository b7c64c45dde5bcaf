#include "render3d/voxel_types.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace geolens::detail {

namespace {

// f(T()) for the C++ type T that `type` stands for.
template <typename F>
auto with_type(VoxelType type, F&& f) {
  switch (type) {
    case VoxelType::int8:
      return f(int8_t());
    case VoxelType::uint8:
      return f(uint8_t());
    case VoxelType::int16:
      return f(int16_t());
    case VoxelType::uint16:
      return f(uint16_t());
    case VoxelType::int32:
      return f(int32_t());
    case VoxelType::uint32:
      return f(uint32_t());
    case VoxelType::float32:
      return f(float());
    case VoxelType::float64:
      return f(double());
  }
  return f(uint8_t());
}

}  // namespace

int voxel_bytes(VoxelType type) {
  return with_type(type, [](auto t) { return int(sizeof(t)); });
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

}  // namespace

void decode_voxels(const unsigned char* data, size_t count, VoxelType type, bool swap, float* out) {
  with_type(type, [&](auto t) {
    using T = decltype(t);
    for (size_t i = 0; i < count; ++i) out[i] = float(load<T>(data + i * sizeof(T), swap));
  });
}

double decode_sample(const unsigned char* data, VoxelType type, bool swap) {
  return with_type(type, [&](auto t) { return double(load<decltype(t)>(data, swap)); });
}

}  // namespace geolens::detail
