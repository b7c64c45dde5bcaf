#include "geolens/io/file_io.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "geolens/core/errors.h"

namespace geolens {

namespace fs = std::filesystem;

void write_file(const std::string& path, const std::string& content) {
  const std::string temporary = path + ".tmp-" + std::to_string(getpid());
  std::error_code error;
  {
    std::ofstream out(temporary, std::ios::binary);
    out << content;
    out.flush();
    if (!out) {
      fs::remove(temporary, error);
      throw IoError("write_file: cannot write '" + path + "'");
    }
  }
  fs::rename(temporary, path, error);
  if (error) {
    fs::remove(temporary, error);
    throw IoError("write_file: cannot write '" + path + "'");
  }
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code error;
  if (fs::exists(b, error) && fs::equivalent(a, b, error)) return true;
  return fs::weakly_canonical(a, error) == fs::weakly_canonical(b, error);
}

}  // namespace geolens
