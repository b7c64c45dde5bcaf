#pragma once
// Writing files so that a failure never leaves a partial one, and the checks before writing.

#include <string>

namespace geolens {

/// Writes `content` to a temporary file in the folder of `path` and renames it into place.
/// Throws IoError naming `path` if writing or renaming fails (the temporary is removed).
void write_file(const std::string& path, const std::string& content);

/// True when `a` and `b` name the same file (or would, once created).
bool same_file(const std::string& a, const std::string& b);

}  // namespace geolens
