// Fuzzes level lists (.levels image pyramids): the input describes a folder (fuzz_support.h: png,
// jpg, raw and dir entries) and, in its lines `line TEXT` (escapes decoded), the list file
// list.levels in it; `size W H` asks for a frame size (0 - 4096). The list is opened with
// open_level_list (what open_source opens a .levels file with) and a level cache of 16 KiB, so
// levels are evicted and made again, and every level is fetched, coarsest first, from its
// corner and across its far edge (clamped). A list naming a path outside the folder is skipped.
// A finding: a crash, a sanitizer report, an exception other than InvalidInput, a hang, an
// allocation past libFuzzer's limit.
#include "fuzz_support.h"
#include "source/level_list.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace geolens;
  const fuzz::fs::path folder = fuzz::scratch() / "folder";
  const fuzz::Description description =
      fuzz::make_files(std::string(reinterpret_cast<const char*>(data), size), folder);
  std::string list;
  SourceFileOptions options;
  for (const std::string& line : description.other) {
    if (line.compare(0, 5, "line ") == 0) list += fuzz::unescape(line.substr(5)) + "\n";
    if (line.compare(0, 5, "size ") == 0) {
      std::istringstream in(line.substr(5));
      int width = 0, height = 0;
      if (in >> width >> height && width >= 0 && width <= 4096 && height >= 0 && height <= 4096) {
        options.width = width;
        options.height = height;
      }
    }
  }
  const std::string path = (folder / "list.levels").string();
  std::ofstream(path, std::ios::binary) << list;
  const std::string inside = fuzz::fs::canonical(folder).string() + "/";
  for (const std::string& image : level_list_images(path)) {
    std::error_code error;
    if (fuzz::fs::weakly_canonical(image, error).string().compare(0, inside.size(), inside) != 0)
      return 0;
  }
  fuzz::read_or_refuse([&] {
    const SourceFile file = open_level_list(path, options, size_t(16) << 10);
    const Source& source = *file.source;
    for (int level = source.levels() - 1; level >= 0; --level) {
      const int width = source.level_width(level), height = source.level_height(level);
      source.fetch(level, 0, 0, std::min(width, 64), std::min(height, 64));
      source.fetch(level, width - 2, height - 2, 4, 4);
    }
  });
  return 0;
}
