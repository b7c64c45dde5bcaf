#pragma once
// The files one run of a tool reads and writes: checked against each other before any work, the
// outputs written to temporary files and renamed into place only once every one is written.

#include <string>
#include <vector>

namespace geolens {

/// Add the inputs, folders and outputs, check(), do the work, write each output to staged(path),
/// then commit(); a run that throws before commit() leaves no output behind. Used by the CLI;
/// any face that writes several files per action (the viewer's exports) wants the same.
class RunFiles {
 public:
  RunFiles() = default;
  RunFiles(const RunFiles&) = delete;
  RunFiles& operator=(const RunFiles&) = delete;
  /// Removes every temporary file, and every folder staged() made, unless commit() ran.
  ~RunFiles();

  /// A file the run reads (`role`: "the input image", ...); no output may be it, and it may not
  /// be a device or a FIFO (check()).
  void add_input(const std::string& role, const std::string& path);
  /// A folder the run reads (`role`: "the input tile folder"); no output may be in it, at any
  /// depth.
  void add_input_folder(const std::string& role, const std::string& path);
  /// A folder given by `option` that holds outputs, made by staged() if it is missing.
  void add_folder(const std::string& option, const std::string& path);
  /// A file given by `option` that the run writes. A symbolic link is followed: the file it
  /// names is written, and the link stays. An existing file that is not a regular one (a
  /// device such as /dev/stdout, a FIFO) is written in place, never replaced.
  void add_output(const std::string& option, const std::string& path);

  /// Throws InvalidInput naming the option and the path when a folder exists as a file or its
  /// parent is missing, or an output is an existing folder, is a symbolic link to nothing, is in
  /// a missing folder that is not an added one or in a folder the run may not write in, is the
  /// same file as an input, is in an input folder or is the same file as another output.
  void check() const;

  /// The temporary file to write the output `path` to: beside the file written, with its
  /// extension (the image format; in the system's temporary folder for an output written in
  /// place). Makes the added folders that are missing. Throws std::logic_error if `path` was not
  /// added.
  std::string staged(const std::string& path);

  /// Copies every output written in place (a device, a FIFO) into it, then renames every other
  /// temporary file into place, one by one: a device that fails (/dev/full) leaves no output
  /// renamed; a rename that fails leaves those before it. Throws IoError naming the output that
  /// failed.
  void commit();

  /// Removes the temporary files and the folders staged() made (if empty) with unlink and rmdir
  /// only, so a signal handler may call it (the CLI's, on SIGINT, SIGTERM and SIGHUP); does
  /// nothing after commit().
  void remove_temporaries() const noexcept;

 private:
  struct Named {
    std::string option, path;  // for an input, its role
  };
  struct Output {
    std::string option, path;
    std::string target;     // the file written: path, or the file its link names
    std::string temporary;  // where it is staged
    bool dangling = false;  // path is a symbolic link to nothing
    bool in_place = false;  // target exists and is not a regular file: copied into, not replaced
  };
  std::vector<Named> inputs_, input_folders_, folders_;
  std::vector<Output> outputs_;
  std::vector<std::string> made_;  // folders staged() made
  bool committed_ = false;
};

}  // namespace geolens
