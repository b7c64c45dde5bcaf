#include "geolens/io/file_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "geolens/core/errors.h"
#include "support/scratch_folder.h"

namespace geolens {
namespace {

namespace fs = std::filesystem;

using FileIo = testing::ScratchFolderTest;

TEST_F(FileIo, WritesTheWholeContentAndLeavesNoTemporary) {
  const std::string path = (dir_ / "a.txt").string();
  write_file(path, "first");
  write_file(path, "second\nline");
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  EXPECT_EQ(s.str(), "second\nline");
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir_)) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "a.txt");
  }
  EXPECT_EQ(files, 1);
}

TEST_F(FileIo, FailureThrowsAndWritesNothing) {
  EXPECT_THROW(write_file((dir_ / "missing" / "a.txt").string(), "x"), IoError);
  fs::create_directories(dir_ / "folder" / "inside");  // a non-empty folder cannot be replaced
  EXPECT_THROW(write_file((dir_ / "folder").string(), "x"), IoError);
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename(), "folder") << entry.path();
}

TEST_F(FileIo, SameFileSeesThroughSpellings) {
  const std::string path = (dir_ / "b.txt").string();
  write_file(path, "x");
  EXPECT_TRUE(same_file(path, (dir_ / "." / "b.txt").string()));
  EXPECT_TRUE(same_file(path, (dir_ / "folder" / ".." / "b.txt").string()));
  EXPECT_TRUE(same_file((dir_ / "new.txt").string(), (dir_ / "." / "new.txt").string()));
  EXPECT_FALSE(same_file(path, (dir_ / "c.txt").string()));
}

}  // namespace
}  // namespace geolens
