#include "geolens/io/file_io.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "geolens/core/errors.h"

namespace geolens {

namespace fs = std::filesystem;

std::string temporary_path(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const fs::path p(path);
  return (p.parent_path() / (p.stem().string() + ".tmp-" + std::to_string(getpid()) + "-" +
                             std::to_string(counter++) + p.extension().string()))
      .string();
}

OutputTarget output_target(const std::string& path) {
  OutputTarget out{path};
  std::error_code error;
  if (fs::is_symlink(fs::symlink_status(path, error))) {
    const fs::path target = fs::canonical(path, error);
    if (!error)
      out.target = target.string();
    else  // a link to nothing, or one that names no path (/dev/stdout -> pipe:[N]): written through
      out.dangling = !fs::exists(fs::status(path, error));
  }
  const fs::file_status status = fs::status(out.target, error);
  out.in_place = !out.dangling && fs::exists(status) && !fs::is_regular_file(status) &&
                 !fs::is_directory(status);
  return out;
}

std::string write_bytes(const std::string& path, const void* data, size_t size) {
  std::string reason;
  if (std::FILE* file = std::fopen(path.c_str(), "wb")) {
    if (std::fwrite(data, 1, size, file) != size) reason = std::strerror(errno);
    if (std::fclose(file) != 0 && reason.empty()) reason = std::strerror(errno);
  } else {
    reason = std::strerror(errno);
  }
  return reason;
}

void write_file(const std::string& path, const void* data, size_t size) {
  const OutputTarget out = output_target(path);
  if (out.dangling)
    throw IoError("write_file: cannot write '" + path + "': a symbolic link to a missing file");
  if (out.in_place) {
    const std::string reason = write_bytes(out.target, data, size);
    if (!reason.empty()) throw IoError("write_file: cannot write '" + path + "': " + reason);
    return;
  }
  const std::string temporary = temporary_path(out.target);
  std::string reason = write_bytes(temporary, data, size);
  std::error_code error;
  if (reason.empty()) {
    fs::rename(temporary, out.target, error);
    if (error) reason = error.message();
  }
  if (!reason.empty()) {
    fs::remove(temporary, error);
    throw IoError("write_file: cannot write '" + path + "': " + reason);
  }
}

void write_file(const std::string& path, const std::string& content) {
  write_file(path, content.data(), content.size());
}

std::string read_file(const std::string& path, const char* function, const std::string& kind,
                      size_t max_bytes) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  require(!std::filesystem::is_directory(status), function,
          "'" + path + "' is a directory, not a " + kind + " file");
  // Read whole, a device never ends (/dev/zero) and a FIFO may never open.
  require(!std::filesystem::exists(status) || std::filesystem::is_regular_file(status), function,
          "'" + path + "' is not a regular file (a device or a FIFO), not a " + kind + " file");
  if (std::filesystem::is_regular_file(status)) {
    const std::uintmax_t size = std::filesystem::file_size(path, error);
    require(error || size <= max_bytes, function,
            "'" + path + "' is larger than the " + std::to_string(max_bytes >> 20) + " MiB a " +
                kind + " file may hold");
  }
  std::ifstream in(path, std::ios::binary);
  require(bool(in), function, "cannot open '" + path + "'");
  std::stringstream text;
  text << in.rdbuf();
  require(!in.bad(), function, "error while reading '" + path + "'");
  return text.str();
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code error;
  if (fs::exists(a, error) && fs::exists(b, error) && fs::equivalent(a, b, error)) return true;
  // Not (both) there yet: compare the absolute, normalized paths ("out.png" and "./out.png",
  // "d/../x" and "x"); weakly_canonical resolves the part that exists.
  const fs::path x = fs::weakly_canonical(fs::absolute(a, error), error);
  if (error) return false;
  const fs::path y = fs::weakly_canonical(fs::absolute(b, error), error);
  return !error && x == y;
}

}  // namespace geolens
