#include "geolens/io/run_files.h"

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

}  // namespace

RunFiles::~RunFiles() {
  if (committed_) return;
  std::error_code error;
  for (const Output& o : outputs_) std::filesystem::remove(o.temporary, error);
  for (auto f = made_.rbegin(); f != made_.rend(); ++f) std::filesystem::remove(*f, error);
}

void RunFiles::add_input(const std::string& role, const std::string& path) {
  inputs_.push_back({role, path});
}

void RunFiles::add_folder(const std::string& option, const std::string& path) {
  folders_.push_back({option, path});
}

void RunFiles::add_output(const std::string& option, const std::string& path) {
  outputs_.push_back({option, path, temporary_path(path)});
}

void RunFiles::check() const {
  namespace fs = std::filesystem;
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
    const std::string parent = fs::path(o.path).parent_path().string();
    bool added = false;
    for (const Named& f : folders_) added = added || same_file(f.path, parent);
    if (!added) require_parent(o.option, o.path);
    for (const Named& in : inputs_)
      require(!same_file(in.path, o.path), option,
              "'" + o.path + "' would overwrite " + in.option + " '" + in.path + "'");
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
  for (const Output& o : outputs_) {
    std::error_code error;
    std::filesystem::rename(o.temporary, o.path, error);
    if (error) throw IoError("cannot write '" + o.path + "': " + error.message());
  }
  committed_ = true;
}

}  // namespace geolens
