#pragma once
// NRRD scalar volumes (.nrrd), read by a small reader of the project's own: Debian's teem
// (libteem-dev) is a 2016 snapshot, and the part of the format a volume needs is a text header
// of "field: value" lines followed by raw or gzip-compressed samples (zlib).

#include <string>

#include "render3d/scalar_volume.h"

namespace geolens {

/// Reads a 3D NRRD file (magic NRRD0001 - NRRD0005) with its data attached after the blank line
/// or detached ("data file: NAME", relative to the header's folder). Fields used: type (the
/// int8 ... uint32, float and double spellings of the format), dimension (3), sizes, encoding
/// (raw, gzip / gz), endian (for multi-byte types), byte skip (bytes of the raw data, -1 = data
/// at the file's end; for gzip, bytes of the inflated data), spacings or space directions (the
/// vectors' lengths; 1 where absent or nan).
/// Other fields and key:=value pairs are ignored. Throws InvalidInput naming "load_nrrd" and the
/// file, with the header line or field at fault: a missing or unknown magic, type or encoding,
/// a dimension other than 3, a size of zero, data that ends before sizes x type bytes (the
/// header claims more data than the file holds), a corrupt gzip stream, more than `max_voxels`
/// voxels (>= 1; the message names the limit) or bytes of samples than volume_bytes_limit.
ScalarVolume load_nrrd(const std::string& path, size_t max_voxels = kMaxVoxels);

/// The file holding the samples of the NRRD at `path` when they are detached ("data file: NAME",
/// relative to the header's folder), from the header alone (its lines up to the blank line, at
/// most 1 MiB read); empty when they are attached or the file is no readable NRRD header (which
/// load_nrrd then names). For the checks a tool makes before its work: such a file is an input.
std::string nrrd_data_path(const std::string& path);

}  // namespace geolens
