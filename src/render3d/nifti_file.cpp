#include "render3d/nifti_file.h"

#include <nifti1_io.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <vector>

#include "geolens/core/errors.h"
#include "render3d/voxel_types.h"

namespace geolens {

namespace {

using detail::VoxelType;

constexpr const char* kReadTypes = "(uint8, int8, int16, uint16, int32, uint32, float32, float64)";

bool voxel_type_of(int datatype, VoxelType& type) {
  switch (datatype) {
    case DT_INT8:
      type = VoxelType::int8;
      return true;
    case DT_UINT8:
      type = VoxelType::uint8;
      return true;
    case DT_INT16:
      type = VoxelType::int16;
      return true;
    case DT_UINT16:
      type = VoxelType::uint16;
      return true;
    case DT_INT32:
      type = VoxelType::int32;
      return true;
    case DT_UINT32:
      type = VoxelType::uint32;
      return true;
    case DT_FLOAT32:
      type = VoxelType::float32;
      return true;
    case DT_FLOAT64:
      type = VoxelType::float64;
      return true;
    default:
      return false;
  }
}

/// What is wrong with the header, from its first 348 bytes (zlib reads plain and gzipped files
/// alike): a short file, not NIfTI-1, a volume of zero size (which libnifti would read as a
/// side of 1); empty when nothing is.
std::string header_problem(const std::string& path) {
  unsigned char header[348] = {};
  gzFile file = gzopen(path.c_str(), "rb");
  if (file == nullptr) return "cannot be opened";
  const int got = gzread(file, header, sizeof header);
  gzclose(file);
  if (got < int(sizeof header))
    return "not a NIfTI-1 file (" + std::to_string(std::max(got, 0)) +
           " bytes, fewer than its 348-byte header)";
  int32_t sizeof_hdr;
  std::memcpy(&sizeof_hdr, header, 4);
  const bool swapped = sizeof_hdr != 348;
  if (swapped && __builtin_bswap32(uint32_t(sizeof_hdr)) != 348)
    return "not a NIfTI-1 file (its header size is not 348)";
  int16_t dim[8];
  std::memcpy(dim, header + 40, sizeof dim);
  if (swapped)
    for (int16_t& d : dim) d = int16_t(__builtin_bswap16(uint16_t(d)));
  if (dim[0] < 1 || dim[0] > 7) return "bad dim[0] = " + std::to_string(dim[0]);
  for (int k = 1; k <= std::min<int>(dim[0], 3); ++k)
    if (dim[k] <= 0)
      return "a volume of zero size (dim[" + std::to_string(k) + "] = " + std::to_string(dim[k]) +
             ")";
  // A voxel type geolens does not read is refused here, before libnifti prints its own "** ERROR"
  // line for one it does not know either.
  int16_t datatype;
  std::memcpy(&datatype, header + 70, 2);
  if (swapped) datatype = int16_t(__builtin_bswap16(uint16_t(datatype)));
  VoxelType type;
  if (!voxel_type_of(datatype, type)) {
    const std::string name = nifti_datatype_string(datatype);  // "**ILLEGAL**" if unknown
    return "voxel type " + (name[0] == '*' ? std::to_string(datatype) : name) + " is not read " +
           kReadTypes;
  }
  // libnifti keeps the offset in an int and reads from byte 348 when it does not fit, so a
  // vox_offset of 3e9 read the wrong bytes instead of being refused.
  uint32_t offset_bits;
  std::memcpy(&offset_bits, header + 108, 4);
  if (swapped) offset_bits = __builtin_bswap32(offset_bits);
  float vox_offset;
  std::memcpy(&vox_offset, &offset_bits, 4);
  if (!(vox_offset >= 0 && vox_offset < 2147483648.0f))
    return "the data offset (vox_offset) " + number_text(vox_offset) +
           " is negative or beyond 2^31 bytes";
  return "";
}

/// The bytes the file holds, uncompressed (zlib reads plain and gzipped files alike), counted up
/// to `enough` (a gzip bomb is not inflated past what the header needs); -1 if it cannot be read.
/// libnifti 3.0.1 zero-fills a short read and reports success, so the reader checks the size
/// itself.
long long data_size(const std::string& path, long long enough) {
  gzFile file = gzopen(path.c_str(), "rb");
  if (file == nullptr) return -1;
  std::vector<char> buffer(size_t(1) << 20);
  long long total = 0;
  int got = 0;
  while (total < enough && (got = gzread(file, buffer.data(), unsigned(buffer.size()))) > 0)
    total += got;
  gzclose(file);
  return got < 0 ? -1 : total;
}

}  // namespace

ScalarVolume load_nifti(const std::string& path, size_t max_voxels) {
  const char* f = "load_nifti";
  require(max_voxels >= 1, f, "max_voxels must be >= 1, got 0");
  const std::string where = "'" + path + "': ";
  require(std::filesystem::is_regular_file(path), f,
          where + (std::filesystem::exists(path) ? "not a file" : "no such file"));
  static std::mutex library;  // libnifti keeps global options; calls are serialized
  std::lock_guard<std::mutex> lock(library);
  nifti_set_debug_level(0);
  const std::string problem = header_problem(path);
  require(problem.empty(), f, where + problem);
  std::unique_ptr<nifti_image, void (*)(nifti_image*)> image(nifti_image_read(path.c_str(), 0),
                                                             nifti_image_free);
  require(image != nullptr, f, where + "libnifti refuses its header");
  ScalarVolume volume;
  volume.nx = image->nx;
  volume.ny = image->ny;
  volume.nz = image->nz;
  require(volume.nx >= 1 && volume.ny >= 1 && volume.nz >= 1, f,
          where + "a volume of zero size (" + std::to_string(image->nx) + " x " +
              std::to_string(image->ny) + " x " + std::to_string(image->nz) + " voxels)");
  const uint64_t voxels = uint64_t(volume.nx) * uint64_t(volume.ny) * uint64_t(volume.nz);
  require(voxels <= max_voxels, f,
          where + std::to_string(volume.nx) + " x " + std::to_string(volume.ny) + " x " +
              std::to_string(volume.nz) + ": " + voxel_limit_message(voxels, max_voxels));
  VoxelType type = VoxelType::uint8;
  require(voxel_type_of(image->datatype, type), f,
          where + "voxel type " + nifti_datatype_string(image->datatype) + " is not read " +
              kReadTypes);
  const size_t count = size_t(volume.nx) * size_t(volume.ny) * size_t(volume.nz);
  const size_t bytes = size_t(image->nvox) * size_t(image->nbyper);
  const std::string claim =
      "the header claims " + std::to_string(volume.nx) + " x " + std::to_string(volume.ny) + " x " +
      std::to_string(volume.nz) + (image->nvox > count ? " x ..." : "") + " " +
      detail::voxel_type_name(type) + " voxels (" + std::to_string(bytes) + " bytes)";
  const size_t max_bytes = volume_bytes_limit(max_voxels);
  require(bytes <= max_bytes, f,
          where + claim + ", more than the " + std::to_string(max_bytes) +
              " bytes of samples read (4 a voxel of max_voxels, at least 2^30)");
  const long long size = data_size(image->iname != nullptr ? image->iname : path,
                                   image->iname_offset + (long long)(bytes));
  require(size >= 0, f, where + "corrupt gzip data");
  const long long held = size - image->iname_offset;
  require(held >= (long long)(bytes), f,
          where + claim + ", the file holds " + std::to_string(std::max(held, 0LL)) +
              " bytes after its header");
  require(nifti_image_load(image.get()) == 0 && image->data != nullptr, f,
          where + claim + ", libnifti could not read them");
  volume.values.resize(count);
  detail::decode_voxels(static_cast<const unsigned char*>(image->data), count, type, false,
                        volume.values.data());
  if (image->scl_slope != 0 && std::isfinite(image->scl_slope) && std::isfinite(image->scl_inter))
    for (float& v : volume.values) v = v * image->scl_slope + image->scl_inter;
  const float spacing[3] = {image->dx, image->dy, image->dz};
  for (int k = 0; k < 3; ++k)
    volume.spacing[k] = std::isfinite(spacing[k]) && spacing[k] != 0 ? std::abs(spacing[k]) : 1;
  check_volume(volume, f, path);
  return volume;
}

}  // namespace geolens
