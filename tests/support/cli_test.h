#pragma once
// A fixture for tests of the real geolens binary: a scratch folder, the run, and the check every
// refusal must pass.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "support/cli_runner.h"
#include "support/scratch_folder.h"

namespace geolens::testing {

class CliTest : public ScratchFolderTest {
 protected:
  /// `GEOLENS_CLI arguments`, its stderr captured in the scratch folder.
  CliRun run(const std::string& arguments) const { return run_cli(arguments, path("stderr.txt")); }

  /// Every file under the scratch folder but the captured stderr, with its bytes.
  std::map<std::string, std::string> files() const {
    std::map<std::string, std::string> contents;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir_)) {
      if (!entry.is_regular_file() || entry.path() == path("stderr.txt")) continue;
      std::ifstream in(entry.path(), std::ios::binary);
      std::stringstream bytes;
      bytes << in.rdbuf();
      contents[entry.path().string()] = bytes.str();
    }
    return contents;
  }

  /// A refusal: exit 2, exactly one line on stderr that mentions `mentions`, and every file as it
  /// was (no output written, no input touched, no temporary left).
  void expect_refused(const std::string& arguments, const std::string& mentions) const {
    SCOPED_TRACE(arguments);
    const std::map<std::string, std::string> before = files();
    const CliRun r = run(arguments);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(mentions), std::string::npos) << r.err;
    EXPECT_TRUE(files() == before) << r.err;
  }
};

}  // namespace geolens::testing
