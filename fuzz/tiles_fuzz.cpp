// Fuzzes tile folders: the input describes a folder (fuzz_support.h: png, jpg, raw and dir
// entries), read two ways:
// - as a folder of XYZ tiles, z/x/y.png (open_source, which opens a folder with
//   open_tile_folder), `size N` asking for a frame of N pixels (0 - 65536);
// - with `tiled W H C T`, as geolens's own <level>/<x>_<y>.png layout: a TiledSource of W x H
//   texels (1 - 1024), C channels and tiles of T texels (1 - 64) reading png_tile_folder, with a
//   cache of 16 KiB (so tiles are evicted and read again).
// Each source is then fetched at the regions of the lines `fetch LEVEL X Y W H` (at most 8; W and
// H 1 - 64, X and Y within +-2^20), or, without such lines, at the corner of its four coarsest
// levels; each fetch on its own, so one refused does not keep the others from running. The
// missing tiles of an XYZ folder are made from coarser zooms.
// A finding: a crash, a sanitizer report, an exception other than InvalidInput, a hang, an
// allocation past libFuzzer's limit.
#include "fuzz_support.h"
#include "geolens/source/source.h"
#include "geolens/source/source_file.h"
#include "source/png_tile_folder.h"

namespace {

struct Region {
  int level, x, y, width, height;
};

void fetch_all(const geolens::Source& source, const std::vector<Region>& regions) {
  std::vector<Region> chosen = regions;
  if (chosen.empty())
    for (int level = source.levels() - 1; level >= std::max(0, source.levels() - 4); --level)
      chosen.push_back({level, 0, 0, std::min(64, source.level_width(level)),
                        std::min(64, source.level_height(level))});
  for (const Region& r : chosen)
    geolens::fuzz::read_or_refuse([&] { source.fetch(r.level, r.x, r.y, r.width, r.height); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace geolens;
  const fuzz::fs::path folder = fuzz::scratch() / "folder";
  const fuzz::Description description =
      fuzz::make_files(std::string(reinterpret_cast<const char*>(data), size), folder);
  SourceFileOptions options;
  std::vector<Region> regions;
  struct {
    int width = 0, height = 0, channels = 0, tile = 0;
  } tiled;
  for (const std::string& line : description.other) {
    std::istringstream in(line);
    std::string word;
    in >> word;
    if (word == "size") {
      int n = 0;
      if (in >> n && n >= 0 && n <= 65536) options.width = n;
    } else if (word == "fetch") {
      Region r{};
      const int reach = 1 << 20;
      if (in >> r.level >> r.x >> r.y >> r.width >> r.height && regions.size() < 8 &&
          r.width >= 1 && r.width <= 64 && r.height >= 1 && r.height <= 64 &&
          std::abs(r.x) <= reach && std::abs(r.y) <= reach)
        regions.push_back(r);
    } else if (word == "tiled") {
      in >> tiled.width >> tiled.height >> tiled.channels >> tiled.tile;
      if (!in || tiled.width < 1 || tiled.width > 1024 || tiled.height < 1 || tiled.height > 1024 ||
          tiled.channels < 1 || tiled.channels > 4 || tiled.tile < 1 || tiled.tile > 64)
        tiled.width = 0;
    }
  }
  fuzz::read_or_refuse([&] {
    const SourceFile file = open_source(folder.string(), options);
    fetch_all(*file.source, regions);
  });
  if (tiled.width > 0)
    fuzz::read_or_refuse([&] {
      TiledSourceOptions chosen;
      chosen.tile_size = tiled.tile;
      chosen.cache_bytes = size_t(16) << 10;
      const TiledSource source(tiled.width, tiled.height, tiled.channels,
                               png_tile_folder(folder.string()), chosen);
      fetch_all(source, regions);
    });
  return 0;
}
