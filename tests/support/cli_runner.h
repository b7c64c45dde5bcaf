#pragma once
// Runs the real geolens binary from a test.

#include <string>

namespace geolens::testing {

struct CliRun {
  int code = -1;    ///< exit code, -1 if the process did not exit normally
  std::string err;  ///< everything it wrote to stderr
};

/// Runs `GEOLENS_CLI arguments` through the shell, stdout discarded, stderr captured in the file
/// `stderr_path` (overwritten) and returned.
CliRun run_cli(const std::string& arguments, const std::string& stderr_path);

}  // namespace geolens::testing
