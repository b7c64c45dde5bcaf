// Every reader that reads a whole file refuses one larger than its kind may hold, by its size,
// before reading it: each file here is sparse (its bytes would be zeros), 1 MiB over the bound.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "geolens/core/errors.h"
#include "geolens/io/geojson.h"
#include "geolens/io/point_csv.h"
#include "geolens/source/map_style.h"
#include "geometry/polygon.h"
#include "render3d/nrrd_file.h"
#include "render3d/obj_file.h"
#include "render3d/ply_file.h"
#include "render3d/transfer_function.h"
#include "source/level_list.h"
#include "source/svg_source.h"
#include "support/scratch_folder.h"

namespace geolens {
namespace {

using ReadBounds = testing::ScratchFolderTest;

struct Bounded {
  std::string name;      // the file's name
  std::string function;  // the reader named in the message
  std::string kind;      // the kind of file named in the message
  int mib;               // the bound
  std::function<void(const std::string&)> read;
};

TEST_F(ReadBounds, EveryWholeFileReaderRefusesAFileOverItsBoundUnread) {
  const Bounded readers[] = {
      {"p.csv", "read_point_csv", "CSV", 256, [](auto& p) { read_point_csv(p); }},
      {"m.geojson", "read_geojson", "GeoJSON", 64, [](auto& p) { read_geojson(p); }},
      {"p.txt", "read_polygon_file", "polygon", 64, [](auto& p) { read_polygon_file(p); }},
      {"s.json", "read_map_style", "style", 16, [](auto& p) { read_map_style(p); }},
      {"l.levels", "open_level_list", "level list", 16, [](auto& p) { open_level_list(p); }},
      {"t.txt", "load_transfer_table", "transfer table", 16,
       [](auto& p) { load_transfer_table(p); }},
      {"page.svg", "open_svg", "SVG", 256, [](auto& p) { open_svg(p); }},
      {"v.nrrd", "load_nrrd", "NRRD", 1025, [](auto& p) { load_nrrd(p); }},
      {"m.obj", "load_obj", "OBJ", 512, [](auto& p) { load_obj(p); }},
      {"m.ply", "load_ply", "PLY", 512, [](auto& p) { load_ply(p); }},
  };
  for (const Bounded& r : readers) {
    const std::string file = path(r.name);
    std::ofstream(file).close();
    std::filesystem::resize_file(file, (size_t(r.mib) + 1) << 20);
    try {
      r.read(file);
      ADD_FAILURE() << r.name << " accepted";
    } catch (const InvalidInput& e) {
      EXPECT_EQ(std::string(e.what()), r.function + ": '" + file + "' is larger than the " +
                                           std::to_string(r.mib) + " MiB a " + r.kind +
                                           " file may hold");
    }
    std::filesystem::remove(file);
  }
}

}  // namespace
}  // namespace geolens
