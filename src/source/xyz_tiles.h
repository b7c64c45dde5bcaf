#pragma once
// A folder of web-map tiles (z/x/y.png, the XYZ or "slippy map" convention) as a source.

#include <cstddef>
#include <string>

#include "geolens/source/source_file.h"

namespace geolens {

/// Opens a folder of XYZ tiles: `path/z/x/y.png` (or .jpg, .jpeg; PNG or JPEG by content), zoom
/// z having 2^z x 2^z tiles of T x T texels over one square extent, tile (0, 0) at the top left
/// (y down, as web maps; TMS's flipped y is not read). T is the size of the root tile 0/0/0.
///
/// The rules, checked when the folder is opened: at least one zoom folder (a subfolder named by
/// a decimal number); every zoom from 0 to the deepest, zmax, present as a folder (a gap is
/// refused, naming the missing folder); the root tile 0/0/0 present, square, of an even size T,
/// with T 2^zmax <= 2^30. A zoom folder may hold only some of its tiles: the common case of a
/// deep zoom covering part of the world.
///
/// The source: T 2^zmax texels square; level l (<= zmax) is zoom zmax - l, read lazily by a
/// TiledSource (tile size T, LRU cache of `cache_bytes`) whose provider reads z/x/y only when a
/// fetch needs it; levels past zmax are the root tile downsampled (downsample.h). A tile missing
/// from its zoom folder falls back to the next coarser zoom that has the tile covering it, whose
/// texels are fetched (through the cache) and upsampled bilinearly (texel centres as Source
/// defines them, clamp-to-edge at the extent). Channels: the root tile's; other tiles are
/// converted to it (grey <-> RGB by luma, alpha added as 255 or dropped).
///
/// Frame: the zoom whose side T 2^z is nearest by ratio to options.width (or else
/// options.height), 1024 when both are 0, the finer on a tie; frame T 2^z square, scale =
/// 2^(zmax - z); level_band 0.25 (labels drawn per zoom). kind "tiles"; counters {"tiles_read", n}
/// (tile files decoded) and
/// {"missing_tiles", n} (tiles made from a coarser zoom; each is counted when it is made, again
/// if made again after an eviction).
///
/// Throws InvalidInput naming "open_tile_folder", the folder and the file at fault for the rules
/// above (a folder in geolens's own <level>/<x>_<y>.png layout, png_tile_folder.h, is named as
/// such: that layout has no size of its own and is read by a TiledSource). A fetch throws
/// InvalidInput naming the file for a tile that fails to decode or whose size is not T x T.
SourceFile open_tile_folder(const std::string& path, const SourceFileOptions& options = {},
                            size_t cache_bytes = size_t(256) << 20);

}  // namespace geolens
