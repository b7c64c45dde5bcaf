#pragma once
// Writing files so that a failure never leaves a partial one, and the checks before writing.

#include <cstddef>
#include <string>

namespace geolens {

/// Writes `size` bytes at `data` to a temporary file in the folder of `path` (its name unique per
/// process and call, so concurrent writes of one path do not collide) and renames it into place,
/// so `path` is never left partial. Throws IoError naming `path` and the reason if writing or
/// renaming fails (the temporary is removed).
void write_file(const std::string& path, const void* data, size_t size);
/// The same for text.
void write_file(const std::string& path, const std::string& content);

/// True when `a` and `b` name the same file (or would, once created).
bool same_file(const std::string& a, const std::string& b);

}  // namespace geolens
