#pragma once
// Private: the words every reader refuses with where a count passes a limit its caller may raise.

#include <algorithm>
#include <cstdint>
#include <string>

namespace geolens {

/// "more than the LIMIT read (NAME; --NAME raises it)": `name` is the reader's parameter, the
/// command-line option the same with '-' for '_' ("max_voxels", "--max-voxels").
inline std::string over_limit(uint64_t limit, const std::string& name) {
  std::string option = name;
  std::replace(option.begin(), option.end(), '_', '-');
  return "more than the " + std::to_string(limit) + " read (" + name + "; --" + option +
         " raises it)";
}

}  // namespace geolens
