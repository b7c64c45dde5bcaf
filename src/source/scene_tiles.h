#pragma once
// A rendered 3D scene as a tiled source: each tile of each level rendered on demand, at that
// level's resolution, by a renderer that draws any region of the view (render3d/camera.h
// PixelRegion).

#include <functional>
#include <memory>

#include "geolens/render3d/camera.h"
#include "geolens/source/source.h"
#include "geolens/source/source_file.h"

namespace geolens {

/// Draws `region` of a view: an RGB Image of region.width x region.height pixels. Thread-safe.
using RegionRenderer = std::function<Image(const PixelRegion& region)>;

/// The region of the view that tile `request` of a scene source covers when its level 0 has 2^k
/// texels per frame pixel (k = detail_levels): pixel_size 2^(level - k) frame pixels, the tile's
/// texel indices as grid indices.
PixelRegion tile_region(const TileRequest& request, int detail_levels);

/// A frame_width x frame_height view as a SourceFile of `kind`: a 3-channel TiledSource of
/// frame_width 2^k x frame_height 2^k texels at level 0 (scale = 2^k, k = detail_levels in
/// [0, 4]) whose every tile of every level is `render(tile_region(request, k))`, so a magnified
/// focus is drawn from a real render at its zoom, not an upsampled picture. Its counters:
/// "tiles_rendered" and "tile_render_seconds" (summed over threads). Throws InvalidInput naming
/// "scene_source" for an empty frame, k outside [0, 4], a level 0 wider or higher than 2^20
/// texels, or invalid tiling options.
SourceFile scene_source(RegionRenderer render, int frame_width, int frame_height, int detail_levels,
                        const TiledSourceOptions& tiling, const std::string& kind);

}  // namespace geolens
