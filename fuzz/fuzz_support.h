#pragma once
// What the fuzz targets share: a scratch folder of the process's own, the input written to a
// file there (the readers take paths), the rule for what a reader may throw, and the small text
// that describes a folder of files (for the readers that take a folder or a list of files).

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/io/image.h"
#include "geolens/source/source_file.h"

namespace geolens::fuzz {

namespace fs = std::filesystem;

/// A folder of this process's own under $TMPDIR (scripts/fuzz.sh points it into build-fuzz/),
/// made on the first call and removed when the process exits normally.
inline const fs::path& scratch() {
  static const fs::path folder = [] {
    const fs::path made = fs::temp_directory_path() / ("geolens-fuzz-" + std::to_string(getpid()));
    fs::remove_all(made);
    fs::create_directories(made);
    std::atexit([] {
      std::error_code error;
      fs::remove_all(scratch(), error);
    });
    return made;
  }();
  return folder;
}

/// Writes `size` bytes at `data` to the file `name` of the scratch folder; returns its path.
inline std::string write_input(const std::string& name, const uint8_t* data, size_t size) {
  const std::string path = (scratch() / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write '%s'\n", path.c_str());
    std::abort();
  }
  return path;
}

/// A bug the target found itself (not a crash): says what and aborts, so libFuzzer keeps the
/// input as a crash.
[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz: finding: %s\n", what.c_str());
  std::abort();
}

/// Runs `read`, the library reading an input. A reader refuses bad input with InvalidInput (its
/// documented contract; the CLI prints the message and exits 2), so that is caught, and printed
/// when the environment sets GEOLENS_FUZZ_VERBOSE (to see why a seed or a replayed input is
/// refused). Any other exception escapes to libFuzzer, which reports it with the input as a
/// crash: a standard one (std::out_of_range, std::length_error ...) is a check the reader missed,
/// and the CLI would report it as an internal failure.
template <class Read>
void read_or_refuse(Read&& read) {
  static const bool verbose = std::getenv("GEOLENS_FUZZ_VERBOSE") != nullptr;
  try {
    read();
    if (verbose) std::fprintf(stderr, "fuzz: read\n");
  } catch (const InvalidInput& e) {
    if (verbose) std::fprintf(stderr, "fuzz: refused: %s\n", e.what());
  }
}

/// Opens `path` as the CLI opens an input (open_source) framed side x side pixels and, if it
/// reads, draws its level 0 whole: the mesh and volume targets' whole work.
inline void open_and_draw(const std::string& path, int side) {
  read_or_refuse([&] {
    SourceFileOptions options;
    options.width = options.height = side;
    const SourceFile file = open_source(path, options);
    const Source& source = *file.source;
    source.fetch(0, 0, 0, source.width(), source.height());
  });
}

/// The description of a folder of files, one entry a line (a fuzz input that stays small and
/// readable, which libFuzzer mutates as text):
///
///     png PATH W H C    a PNG of W x H pixels (1 - 64 each), C channels (1 - 4), save_image's
///     jpg PATH W H      a JPEG of W x H pixels (1 - 64 each)
///     raw PATH BYTES    a file holding BYTES as written, \n, \t, \\ and \xHH decoded
///     dir PATH          a folder
///
/// PATH is relative, at most 4 names of letters, digits, '.', '_' and '-' (not "." or ".."),
/// separated by '/': so nothing is written, or read, outside the folder. An entry that breaks
/// these rules, or whose file cannot be made (its folder is a file), is left out; so are entries
/// past the 64th. The pixels are a fixed pattern of their coordinates.
struct Description {
  std::vector<std::string> other;  ///< the lines that are none of the entries, in order
};

/// BYTES with its escapes decoded.
inline std::string unescape(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\\' || i + 1 == text.size()) {
      out += text[i];
      continue;
    }
    const char c = text[++i];
    if (c == 'n') {
      out += '\n';
    } else if (c == 't') {
      out += '\t';
    } else if (c == 'x' && i + 2 < text.size() &&
               std::isxdigit(static_cast<unsigned char>(text[i + 1])) &&
               std::isxdigit(static_cast<unsigned char>(text[i + 2]))) {
      out += char(std::stoi(text.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += c;
    }
  }
  return out;
}

/// Whether PATH keeps to the rules above.
inline bool safe_path(const std::string& path) {
  if (path.empty() || path.size() > 64 || path.front() == '/' || path.back() == '/') return false;
  int names = 0;
  std::istringstream parts(path);
  for (std::string name; std::getline(parts, name, '/');) {
    if (name.empty() || name == "." || name == ".." || ++names > 4) return false;
    for (const char c : name)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-')
        return false;
  }
  return true;
}

/// An image of the fixed pattern.
inline Image pattern(int width, int height, int channels) {
  Image image(width, height, channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c) image.at(x, y)[c] = uint8_t(x * 37 + y * 11 + c * 71);
  return image;
}

/// Makes the files `text` describes in `folder` (emptied first); returns the other lines.
inline Description make_files(const std::string& text, const fs::path& folder) {
  std::error_code error;
  fs::remove_all(folder, error);
  fs::create_directories(folder);
  Description description;
  std::istringstream lines(text);
  int entries = 0;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string kind, path;
    words >> kind >> path;
    const bool entry = kind == "png" || kind == "jpg" || kind == "raw" || kind == "dir";
    if (!entry) {
      description.other.push_back(line);
      continue;
    }
    if (!safe_path(path) || ++entries > 64) continue;
    const fs::path file = folder / path;
    fs::create_directories(file.parent_path(), error);
    if (error) continue;
    if (kind == "dir") {
      fs::create_directories(file, error);
    } else if (kind == "raw") {
      std::string bytes;
      std::getline(words >> std::ws, bytes);
      std::ofstream(file, std::ios::binary) << unescape(bytes);
    } else {
      int width = 0, height = 0, channels = 3;
      words >> width >> height;
      if (kind == "png") words >> channels;
      if (width < 1 || width > 64 || height < 1 || height > 64 || channels < 1 || channels > 4)
        continue;
      // Encoded outside the folder (save_image picks the format by extension; PATH may name a
      // folder), then moved to PATH.
      const fs::path encoded = scratch() / (kind == "png" ? "encoded.png" : "encoded.jpg");
      try {
        save_image(encoded.string(), pattern(width, height, channels));
      } catch (const std::exception& e) {
        finding(std::string("save_image of a valid image failed: ") + e.what());
      }
      fs::rename(encoded, file, error);
    }
  }
  return description;
}

}  // namespace geolens::fuzz
