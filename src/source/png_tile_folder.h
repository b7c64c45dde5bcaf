#pragma once
// Tiles read from a folder of image files, one per tile and level.

#include <string>

#include "geolens/source/source.h"

namespace geolens {

/// A TileProvider reading tile (tile_x, tile_y) of level `level` from the file
/// `directory/<level>/<tile_x>_<tile_y>.png` (decimal numbers; decoded by load_image, so PNG or
/// JPEG by content). Thread-safe. The provider throws InvalidInput naming "png_tile_folder" and
/// the file when the file is missing, unreadable or corrupt, or when its size or channel count
/// is not the requested tile's.
TileProvider png_tile_folder(const std::string& directory);

/// The path png_tile_folder reads tile (tile_x, tile_y) of `level` from.
std::string png_tile_path(const std::string& directory, int level, int tile_x, int tile_y);

}  // namespace geolens
