#pragma once
// Writing files so that a failure never leaves a partial one, the checks before writing, and
// reading a text file whole.

#include <cstddef>
#include <limits>
#include <string>

namespace geolens {

/// A name for a temporary file beside `path`, with its extension (so a writer that picks its
/// format by extension still does): STEM.tmp-PID-N.EXT, N counting the calls of this process, so
/// two temporaries of one path never collide, within a process or between processes.
std::string temporary_path(const std::string& path);

/// The file an output named `path` writes. `target` is `path`, or the file a symbolic link
/// names (the link stays: /dev/stdout is written through, not replaced); `dangling` when `path`
/// is a link to nothing; `in_place` when the target exists and is not a regular file or a
/// folder (a device, a FIFO): written into, never replaced by a renamed temporary.
struct OutputTarget {
  std::string target;  ///< the file written: `path`, or what the link at `path` names
  ///@{
  bool dangling = false, in_place = false;  ///< as above: a link to nothing; written into
  ///@}
};
/// The OutputTarget of `path`, found without writing anything; never throws (a path that does not
/// exist yet is its own target, neither dangling nor in place).
OutputTarget output_target(const std::string& path);

/// Writes `size` bytes at `data` to `path` opened for writing (made, or emptied: a temporary, a
/// device, a FIFO), as it is; returns the reason it failed, empty if it did not.
std::string write_bytes(const std::string& path, const void* data, size_t size);

/// Writes `size` bytes at `data` to `path` (output_target: through a link, into a device or a
/// FIFO with write_bytes), else to a temporary file in its folder (temporary_path) renamed into
/// place, so `path` is never left partial. Throws IoError naming `path` and the reason if `path` is
/// a link to nothing or writing or renaming fails (the temporary is removed).
void write_file(const std::string& path, const void* data, size_t size);
/// The same for text.
void write_file(const std::string& path, const std::string& content);

/// The bytes of the file at `path`. Throws InvalidInput, naming `function`, if `path` is a folder
/// ("'PATH' is a directory, not a KIND file"), a device or a FIFO, holds more than `max_bytes`
/// ("'PATH' is larger than the N MiB a KIND file may hold", before it is read), cannot be opened
/// or fails while read.
std::string read_file(const std::string& path, const char* function, const std::string& kind,
                      size_t max_bytes = std::numeric_limits<size_t>::max());

/// True when `a` and `b` name the same file (or would, once created).
bool same_file(const std::string& a, const std::string& b);

}  // namespace geolens
