#include "geolens/io/run_files.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "geolens/core/errors.h"
#include "geolens/io/file_io.h"

namespace geolens {

namespace {

void require_parent(const std::string& option, const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  require(parent.empty() || std::filesystem::is_directory(parent), option.c_str(),
          "folder '" + parent.string() + "' of '" + path + "' does not exist");
}

// Whether `path` is in the folder `folder` at any depth, both resolved as far as they exist.
bool inside(const std::string& path, const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::path p = fs::weakly_canonical(fs::absolute(path, error), error);
  const fs::path f = fs::weakly_canonical(fs::absolute(folder, error), error);
  if (error) return false;
  auto a = p.begin(), b = f.begin();
  for (; a != p.end() && b != f.end(); ++a, ++b) {
    if (b->empty()) break;  // the trailing separator of "folder/"
    if (*a != *b) return false;
  }
  return (b == f.end() || b->empty()) && a != p.end();
}

}  // namespace

RunFiles::~RunFiles() { remove_temporaries(); }

void RunFiles::remove_temporaries() const noexcept {
  if (committed_) return;
  for (const Output& o : outputs_) ::unlink(o.temporary.c_str());
  for (auto f = made_.rbegin(); f != made_.rend(); ++f) ::rmdir(f->c_str());
}

void RunFiles::add_input(const std::string& role, const std::string& path) {
  inputs_.push_back({role, path});
}

void RunFiles::add_input_folder(const std::string& role, const std::string& path) {
  input_folders_.push_back({role, path});
}

void RunFiles::add_folder(const std::string& option, const std::string& path) {
  folders_.push_back({option, path});
}

void RunFiles::add_output(const std::string& option, const std::string& path) {
  namespace fs = std::filesystem;
  const OutputTarget out = output_target(path);
  std::error_code error;
  // An output written in place is staged where the run may make files, with its extension.
  const std::string temporary = temporary_path(
      out.in_place ? (fs::temp_directory_path(error) / fs::path(out.target).filename()).string()
                   : out.target);
  outputs_.push_back({option, path, out.target, temporary, out.dangling, out.in_place});
}

void RunFiles::check() const {
  namespace fs = std::filesystem;
  // Read whole, a device never ends (/dev/zero filled the memory) and a FIFO may never open.
  for (const Named& in : inputs_) {
    std::error_code error;
    const fs::file_status status = fs::status(in.path, error);
    require(!fs::exists(status) || fs::is_regular_file(status) || fs::is_directory(status),
            in.option.c_str(), "'" + in.path + "' is not a regular file (a device or a FIFO)");
  }
  for (const Named& f : folders_) {
    if (fs::exists(f.path))
      require(fs::is_directory(f.path), f.option.c_str(),
              "'" + f.path + "' exists and is not a folder");
    else
      require_parent(f.option, f.path);
  }
  for (size_t k = 0; k < outputs_.size(); ++k) {
    const Output& o = outputs_[k];
    const char* option = o.option.c_str();
    require(!fs::is_directory(o.path), option, "'" + o.path + "' is an existing folder");
    require(!o.dangling, option, "'" + o.path + "' is a symbolic link to a file that is missing");
    const std::string parent = fs::path(o.target).parent_path().string();
    bool added = false;
    for (const Named& f : folders_) added = added || same_file(f.path, parent);
    if (!added) require_parent(o.option, o.target);
    // Checked now, not found once the work is done; errno read after access() sets it (a
    // function's arguments are evaluated in no set order).
    if (o.in_place) {
      const bool writable = ::access(o.target.c_str(), W_OK) == 0;
      require(writable, option, "cannot write '" + o.path + "': " + std::strerror(errno));
    } else if (!added) {
      const bool writable = ::access(parent.empty() ? "." : parent.c_str(), W_OK | X_OK) == 0;
      require(writable, option,
              "cannot write in the folder of '" + o.path + "': " + std::strerror(errno));
    }
    for (const Named& in : inputs_)
      require(!same_file(in.path, o.path), option,
              "'" + o.path + "' would overwrite " + in.option + " '" + in.path + "'");
    for (const Named& in : input_folders_)
      require(!inside(o.target, in.path), option,
              "'" + o.path + "' is inside " + in.option + " '" + in.path + "'");
    for (size_t j = 0; j < k; ++j)
      require(!same_file(outputs_[j].path, o.path), option,
              "'" + o.path + "' is the same file as " + outputs_[j].option + " '" +
                  outputs_[j].path + "'");
  }
}

std::string RunFiles::staged(const std::string& path) {
  for (const Named& f : folders_) {
    if (std::filesystem::create_directory(f.path)) made_.push_back(f.path);
  }
  for (const Output& o : outputs_)
    if (o.path == path) return o.temporary;
  throw std::logic_error("RunFiles::staged: '" + path + "' is not an output");
}

void RunFiles::commit() {
  // Devices and FIFOs first, their bytes written into them (the staged file removed either way):
  // a write that fails there (/dev/full) leaves no regular output renamed into place.
  for (const Output& o : outputs_) {
    if (!o.in_place) continue;
    const std::string bytes = read_file(o.temporary, "RunFiles::commit", "staged");
    std::error_code error;
    std::filesystem::remove(o.temporary, error);
    const std::string reason = write_bytes(o.target, bytes.data(), bytes.size());
    if (!reason.empty()) throw IoError("cannot write '" + o.path + "': " + reason);
  }
  for (const Output& o : outputs_) {
    if (o.in_place) continue;
    std::error_code error;
    std::filesystem::rename(o.temporary, o.target, error);
    if (error) throw IoError("cannot write '" + o.path + "': " + error.message());
  }
  committed_ = true;
}

}  // namespace geolens
