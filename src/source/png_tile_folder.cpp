#include "source/png_tile_folder.h"

#include <filesystem>
#include <string>

#include "geolens/core/errors.h"

namespace geolens {

std::string png_tile_path(const std::string& directory, int level, int tile_x, int tile_y) {
  return (std::filesystem::path(directory) / std::to_string(level) /
          (std::to_string(tile_x) + "_" + std::to_string(tile_y) + ".png"))
      .string();
}

TileProvider png_tile_folder(const std::string& directory) {
  return [directory](const TileRequest& request) {
    const std::string path =
        png_tile_path(directory, request.level, request.tile_x, request.tile_y);
    Image tile;
    try {
      tile = load_image(path);
    } catch (const InvalidInput& e) {
      throw InvalidInput(std::string("png_tile_folder: ") + e.what());
    }
    require(tile.width == request.width && tile.height == request.height &&
                tile.channels == request.channels,
            "png_tile_folder",
            "'" + path + "' is " + std::to_string(tile.width) + " x " +
                std::to_string(tile.height) + " with " + std::to_string(tile.channels) +
                " channels, expected " + std::to_string(request.width) + " x " +
                std::to_string(request.height) + " with " + std::to_string(request.channels));
    return tile;
  };
}

}  // namespace geolens
