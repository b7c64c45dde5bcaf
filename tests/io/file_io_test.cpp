#include "geolens/io/file_io.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "geolens/core/errors.h"
#include "support/scratch_folder.h"

namespace geolens {
namespace {

namespace fs = std::filesystem;

using FileIo = testing::ScratchFolderTest;

// What write_file throws for `path`, empty if it does not.
std::string write_file_error(const std::string& path) {
  try {
    write_file(path, "x");
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

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

TEST_F(FileIo, TemporariesSitBesideTheirFileKeepTheExtensionAndNeverRepeat) {
  const std::string path = (dir_ / "out.png").string();
  const fs::path a(temporary_path(path)), b(temporary_path(path));
  EXPECT_NE(a, b);
  EXPECT_EQ(a.parent_path(), dir_);
  EXPECT_EQ(a.extension(), ".png");
  EXPECT_EQ(a.filename().string().rfind("out.tmp-", 0), 0u) << a;
}

// The library's own writes (the viewer's exports, Python's) follow links and write into a FIFO
// or a device rather than replace it, as the CLI's outputs do.
TEST_F(FileIo, WritesThroughLinksAndIntoSpecialFiles) {
  const std::string real = (dir_ / "real.txt").string(), link = (dir_ / "link.txt").string();
  write_file(real, "old");
  fs::create_symlink("real.txt", link);
  write_file(link, "new");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read_file(real, "test", "text"), "new");
  fs::create_symlink("missing.txt", dir_ / "dangling.txt");
  EXPECT_THROW(write_file((dir_ / "dangling.txt").string(), "x"), IoError);
  EXPECT_FALSE(fs::exists(dir_ / "missing.txt"));
  const std::string fifo = (dir_ / "fifo.txt").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string read_back;
  std::thread reader([&] {
    std::ifstream in(fifo);
    read_back.assign(std::istreambuf_iterator<char>(in), {});
  });
  write_file(fifo, "through");
  reader.join();
  EXPECT_EQ(read_back, "through");
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_NE(write_file_error("/dev/full"), "");
}

TEST_F(FileIo, SameFileSeesThroughSpellings) {
  const std::string path = (dir_ / "b.txt").string();
  write_file(path, "x");
  EXPECT_TRUE(same_file(path, (dir_ / "." / "b.txt").string()));
  EXPECT_TRUE(same_file(path, (dir_ / "folder" / ".." / "b.txt").string()));
  EXPECT_TRUE(same_file((dir_ / "new.txt").string(), (dir_ / "." / "new.txt").string()));
  EXPECT_FALSE(same_file(path, (dir_ / "c.txt").string()));
  // Relative spellings of a file that does not exist yet, from the working folder.
  const fs::path here = fs::current_path();
  fs::current_path(dir_);
  EXPECT_TRUE(same_file("out.png", "./out.png"));
  EXPECT_TRUE(same_file("out.png", (dir_ / "out.png").string()));
  EXPECT_FALSE(same_file("out.png", "other.png"));
  fs::current_path(here);
}

}  // namespace
}  // namespace geolens

#include "geolens/io/run_files.h"

namespace geolens {
namespace {

using RunFilesTest = testing::ScratchFolderTest;

// Outputs reach their paths only at commit(); a run abandoned before leaves nothing.
TEST_F(RunFilesTest, OutputsAppearOnlyWhenTheRunCommits) {
  const std::string a = (dir_ / "a.txt").string(), b = (dir_ / "b.txt").string();
  {
    RunFiles files;
    files.add_output("-o", a);
    files.add_output("--stats", b);
    files.check();
    write_file(files.staged(a), "1");
    EXPECT_FALSE(fs::exists(a));  // abandoned here
  }
  EXPECT_TRUE(fs::is_empty(dir_));
  RunFiles files;
  files.add_output("-o", a);
  files.add_output("--stats", b);
  files.check();
  write_file(files.staged(a), "1");
  write_file(files.staged(b), "2");
  files.commit();
  std::ifstream in(a);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "1");
  EXPECT_TRUE(fs::exists(b));
}

TEST_F(RunFilesTest, ClashesAreRefusedBeforeAnyWork) {
  const std::string in = (dir_ / "in.png").string();
  write_file(in, "x");
  fs::create_directory(dir_ / "folder");
  auto refused = [&](const std::vector<std::pair<std::string, std::string>>& outputs) {
    RunFiles files;
    files.add_input("the input image", in);
    for (const auto& [option, path] : outputs) files.add_output(option, path);
    try {
      files.check();
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(refused({{"-o", in}}).find("would overwrite the input image"), std::string::npos);
  EXPECT_NE(refused({{"-o", (dir_ / "o.png").string()}, {"--stats", (dir_ / "./o.png").string()}})
                .find("is the same file as -o"),
            std::string::npos);
  EXPECT_NE(refused({{"-o", (dir_ / "folder").string()}}).find("is an existing folder"),
            std::string::npos);
  EXPECT_NE(refused({{"-o", (dir_ / "missing" / "o.png").string()}}).find("does not exist"),
            std::string::npos);
  EXPECT_EQ(refused({{"-o", (dir_ / "o.png").string()}}), "");
}

// A folder the run reads (a tile folder) holds no output at any depth, however spelled; a
// sibling folder whose name starts with its name is not in it.
TEST_F(RunFilesTest, NoOutputInsideAnInputFolder) {
  fs::create_directories(dir_ / "tiles" / "3" / "2");
  fs::create_directories(dir_ / "tiles2");
  auto why = [&](const std::string& output) {
    RunFiles files;
    files.add_input_folder("the input tile folder", (dir_ / "tiles").string());
    files.add_output("-o", output);
    try {
      files.check();
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(why((dir_ / "tiles" / "3" / "2" / "1.png").string()).find("is inside the input tile"),
            std::string::npos);
  EXPECT_NE(why((dir_ / "tiles2" / ".." / "tiles" / "o.png").string()).find("is inside"),
            std::string::npos);
  EXPECT_EQ(why((dir_ / "tiles2" / "o.png").string()), "");
  EXPECT_EQ(why((dir_ / "o.png").string()), "");
}

// A link is followed (the file it names is written, the link stays), a link to nothing is refused,
// and a file that is not a regular one is written into, never replaced (`--stats /dev/stdout` had
// replaced /dev/stdout's link with a regular file, run as root).
TEST_F(RunFilesTest, LinksAreFollowedAndSpecialFilesWrittenInPlace) {
  const std::string real = (dir_ / "real.json").string(), link = (dir_ / "link.json").string();
  write_file(real, "old");
  fs::create_symlink("real.json", link);
  fs::create_symlink("missing.json", dir_ / "dangling.json");
  const std::string fifo = (dir_ / "fifo.json").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  {
    RunFiles files;
    files.add_output("--stats", (dir_ / "dangling.json").string());
    try {
      files.check();
      ADD_FAILURE() << "a link to nothing was accepted";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("symbolic link to a file that is missing"),
                std::string::npos);
    }
  }
  std::string read_back;
  std::thread reader([&] {
    std::ifstream in(fifo);
    read_back.assign(std::istreambuf_iterator<char>(in), {});
  });
  {
    RunFiles files;
    files.add_output("--stats", link);
    files.add_output("--output", fifo);
    files.check();
    write_file(files.staged(link), "new");
    write_file(files.staged(fifo), "through the fifo");
    EXPECT_FALSE(fs::path(files.staged(fifo)).string().starts_with(dir_.string()));
    files.commit();
  }
  reader.join();
  EXPECT_EQ(read_back, "through the fifo");
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read_file(real, "test", "stats"), "new");
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names,
            (std::vector<std::string>{"dangling.json", "fifo.json", "link.json", "real.json"}));
}

// What a signal handler calls: the staged files and the folders made for them go, the outputs
// never appear.
TEST_F(RunFilesTest, RemoveTemporariesLeavesNothingBehind) {
  const std::string folder = (dir_ / "made").string(), out = (dir_ / "made" / "o.txt").string();
  RunFiles files;
  files.add_folder("--output", folder);
  files.add_output("--output", out);
  files.check();
  write_file(files.staged(out), "1");
  EXPECT_TRUE(fs::exists(folder));
  files.remove_temporaries();
  EXPECT_TRUE(fs::is_empty(dir_));
}

}  // namespace
}  // namespace geolens
