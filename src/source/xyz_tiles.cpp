#include "source/xyz_tiles.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/source/source.h"
#include "source/convert_channels.h"
#include "source/downsample.h"

namespace geolens {

namespace {

namespace fs = std::filesystem;

constexpr const char* kFn = "open_tile_folder";

/// `path` in single quotes.
std::string in_quotes(const fs::path& path) {
  std::string text(1, '\'');
  text += path.string();
  text += '\'';
  return text;
}

/// What the provider of a tile folder shares with the counters.
struct TileFolder {
  fs::path folder;
  int zmax = 0;
  int tile = 0;      ///< T, texels per tile side
  int channels = 0;  ///< the root tile's
  Image root;        ///< tile 0/0/0, converted
  std::string root_path;
  const Source* source = nullptr;  ///< the TiledSource this provider feeds; set once it exists
  std::atomic<size_t> read{0}, missing{0};

  /// The file of tile (z, x, y), or an empty path when the folder has none.
  fs::path file(int z, int x, int y) const {
    const fs::path base = folder / std::to_string(z) / std::to_string(x);
    for (const char* ext : {".png", ".jpg", ".jpeg"}) {
      fs::path candidate = base / (std::to_string(y) + ext);
      std::error_code error;
      if (fs::is_regular_file(candidate, error)) return candidate;
    }
    return {};
  }

  /// Decodes the tile at `file`, which must be T x T, converted to `channels`.
  Image load(const fs::path& file) const {
    Image tile;
    try {
      tile = load_image(file.string());
    } catch (const InvalidInput& e) {
      throw InvalidInput(std::string(kFn) + ": " + e.what());
    }
    require(tile.width == this->tile && tile.height == this->tile, kFn,
            in_quotes(file) + " is " + std::to_string(tile.width) + " x " +
                std::to_string(tile.height) + ", but the tiles of " + in_quotes(folder) + " are " +
                std::to_string(this->tile) + " x " + std::to_string(this->tile) + " (as " +
                in_quotes(root_path) + "): tiles of mixed sizes");
    return convert_channels(std::move(tile), channels);
  }

  Image provide(const TileRequest& r) {
    if (r.level > zmax) {  // past the root: the root downsampled
      Image tile = root;
      for (int l = zmax; l < r.level; ++l) tile = downsample(tile);
      return tile;
    }
    const int z = zmax - r.level;
    if (z == 0) return root;
    if (const fs::path found = file(z, r.tile_x, r.tile_y); !found.empty()) {
      Image tile = load(found);
      ++read;
      return tile;
    }
    ++missing;
    // The nearest coarser zoom with the tile covering this one (the root always has it).
    int d = 1;
    while (d < z && file(z - d, r.tile_x >> d, r.tile_y >> d).empty()) ++d;
    // Texel X of this level has its centre at (X + 0.5) / 2^d - 0.5 in the coarse level's texels.
    const double step = std::ldexp(1.0, -d);
    auto coarse = [&](int fine) { return (fine + 0.5) * step - 0.5; };
    const int cx0 = int(std::floor(coarse(r.x))), cy0 = int(std::floor(coarse(r.y)));
    const int cx1 = int(std::floor(coarse(r.x + r.width - 1))) + 1;
    const int cy1 = int(std::floor(coarse(r.y + r.height - 1))) + 1;
    const TexelRegion region = source->fetch(r.level + d, cx0, cy0, cx1 - cx0 + 1, cy1 - cy0 + 1);
    Image tile(r.width, r.height, channels);
    for (int j = 0; j < r.height; ++j) {
      const double cy = coarse(r.y + j);
      const int y0 = int(std::floor(cy));
      const double fy = cy - y0;
      for (int i = 0; i < r.width; ++i) {
        const double cx = coarse(r.x + i);
        const int x0 = int(std::floor(cx));
        const double fx = cx - x0;
        const uint8_t *a = region.at(x0, y0), *b = region.at(x0 + 1, y0);
        const uint8_t *c = region.at(x0, y0 + 1), *e = region.at(x0 + 1, y0 + 1);
        uint8_t* out = tile.at(i, j);
        for (int k = 0; k < channels; ++k) {
          const double top = a[k] + (b[k] - a[k]) * fx, bottom = c[k] + (e[k] - c[k]) * fx;
          out[k] = uint8_t(std::lround(top + (bottom - top) * fy));
        }
      }
    }
    return tile;
  }
};

/// True when `name` is a decimal number of at most 2 digits (a zoom).
bool is_zoom(const std::string& name) {
  return !name.empty() && name.size() <= 2 &&
         std::all_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; });
}

/// The deepest zoom of the tile folder `path` (`folder`): its zoom folders 0, 1, 2, ... up to it,
/// refused if there is none, one is missing or it is above 30.
int deepest_zoom(const std::string& path, const fs::path& folder) {
  // The listing's error is the iterator's alone (a range-for's ++ would throw it as a
  // filesystem_error); an entry whose type cannot be read (a dangling link) is no zoom folder.
  std::error_code error;
  std::set<int> zooms;
  fs::directory_iterator entry(path, error);
  for (; !error && entry != fs::directory_iterator(); entry.increment(error)) {
    std::error_code type_error;
    if (entry->is_directory(type_error) && is_zoom(entry->path().filename().string()))
      zooms.insert(std::stoi(entry->path().filename().string()));
  }
  require(!error, kFn, "'" + path + "' cannot be listed: " + error.message());
  require(!zooms.empty(), kFn,
          "'" + path + "' has no zoom folders (subfolders 0, 1, 2, ... holding x/y.png tiles)");
  const int zmax = *zooms.rbegin();
  // Tiles of at least 2 px at zoom 30 already make 2^31 texels a side, past the limit below; a
  // larger zoom would shift the sizes out of their integers.
  require(zmax <= 30, kFn,
          "'" + path + "' has a zoom folder " + std::to_string(zmax) +
              ": zooms above 30 (2^30 texels a side) are not read");
  for (int z = 0; z <= zmax; ++z)
    require(zooms.count(z) > 0, kFn,
            "'" + path + "' has zooms up to " + std::to_string(zmax) + " but no '" +
                (folder / std::to_string(z)).string() + "': a missing zoom level");
  return zmax;
}

/// Reads the root tile, 0/0/0, into `state` (its path, size, channels and pixels; counted as
/// read), refusing a missing one, a tile not square or of an odd size, or one too large for
/// state.zmax.
void read_root_tile(const std::string& path, TileFolder& state) {
  const fs::path root = state.file(0, 0, 0);
  if (root.empty()) {
    // geolens's own layout, <level>/<x>_<y>.png, has files where XYZ has x folders.
    std::error_code error;
    const bool own_layout = fs::is_regular_file(state.folder / "0" / "0_0.png", error);
    require(false, kFn,
            in_quotes(state.folder / "0" / "0" / "0.png") + " (the root tile) is missing" +
                (own_layout ? "; '" + path +
                                  "' is in png_tile_folder's <level>/<x>_<y>.png layout, which "
                                  "has no size of its own: read it with a TiledSource"
                            : std::string()));
  }
  state.root_path = root.string();
  Image root_tile;
  try {
    root_tile = load_image(state.root_path);
  } catch (const InvalidInput& e) {
    throw InvalidInput(std::string(kFn) + ": " + e.what());
  }
  ++state.read;
  const int T = root_tile.width;
  require(root_tile.width == root_tile.height, kFn,
          "'" + state.root_path + "' is " + std::to_string(root_tile.width) + " x " +
              std::to_string(root_tile.height) + ": tiles must be square");
  require(T % 2 == 0, kFn,
          "'" + state.root_path + "' is " + std::to_string(T) + " x " + std::to_string(T) +
              ": the tile size must be even");
  require((int64_t(T) << state.zmax) <= (int64_t(1) << 30), kFn,
          "'" + path + "': " + std::to_string(T) + " px tiles at zoom " +
              std::to_string(state.zmax) + " exceed 2^30 texels a side");
  state.tile = T;
  state.channels = root_tile.channels;
  state.root = std::move(root_tile);
}

/// The zoom whose side (T << zoom texels) is nearest, by ratio, the frame size asked (its width,
/// else its height, else 1024), the deeper one on a tie.
int frame_zoom(int T, int zmax, const SourceFileOptions& options) {
  const int target =
      options.width > 0 ? options.width : (options.height > 0 ? options.height : 1024);
  int best = zmax;
  for (int z = zmax - 1; z >= 0; --z)
    if (std::abs(std::log(double(T << z) / target)) <
        std::abs(std::log(double(T << best) / target)) - 1e-12)
      best = z;
  return best;
}

}  // namespace

SourceFile open_tile_folder(const std::string& path, const SourceFileOptions& options,
                            size_t cache_bytes) {
  require(options.width >= 0 && options.height >= 0, kFn,
          "the frame size must be >= 0, got " + std::to_string(options.width) + " x " +
              std::to_string(options.height));
  std::error_code error;
  require(fs::is_directory(path, error), kFn, "'" + path + "' is not a folder");
  auto state = std::make_shared<TileFolder>();
  state->folder = path;
  state->zmax = deepest_zoom(path, state->folder);
  read_root_tile(path, *state);
  const int T = state->tile;

  TiledSourceOptions tiled;
  tiled.tile_size = T;
  tiled.cache_bytes = cache_bytes;
  const int side = T << state->zmax;
  auto source = std::make_shared<const TiledSource>(
      side, side, state->channels,
      [state](const TileRequest& request) { return state->provide(request); }, tiled);
  state->source = source.get();

  const int zoom = frame_zoom(T, state->zmax, options);
  SourceFile file;
  file.frame_width = file.frame_height = T << zoom;
  file.scale = std::ldexp(1.0, state->zmax - zoom);
  file.kind = "tiles";
  // Each zoom is drawn on its own (labels, line widths): blended only about their midpoint.
  file.level_band = 0.25;
  // The counters keep the state, not the source: the provider inside the source owns the state.
  file.counters = [state] {
    return std::vector<std::pair<std::string, double>>{{"tiles_read", double(state->read)},
                                                       {"missing_tiles", double(state->missing)}};
  };
  file.source = std::move(source);
  return file;
}

}  // namespace geolens
