#pragma once
// A vector map as a source: GeoJSON layers in longitude and latitude, projected, styled
// (map_style.h) and drawn anti-aliased with cairo per tile at the resolution each tile is shown
// at, so the focus of a lens shows finer lines and the layers of its zoom; its points' labels
// are placed on the output after rendering (map_labels.h), upright and unmagnified.

#include <string>
#include <vector>

#include "geolens/io/vector_data.h"
#include "geolens/source/map_style.h"
#include "geolens/source/source_file.h"
#include "source/map_labels.h"

namespace geolens {

/// How much finer than the frame a vector map's level 0 is: 2^kVectorMapDetail texels per frame
/// pixel (8).
constexpr int kVectorMapDetail = 3;

/// The frame width of a vector map when no size is given, pixels.
constexpr int kVectorMapDefaultWidth = 1024;

/// `data` (coordinates are longitude, latitude in degrees, WGS84, as GeoJSON has them: x east,
/// y north) drawn in `style`.
///
/// The frame shows style.extent, or else the bounding box of every feature, projected
/// (style.projection): `width` x `height` pixels; with height 0 it follows the projected
/// extent's aspect (width 0: kVectorMapDefaultWidth), with both given the extent is centred
/// and scaled uniformly to fit (the map is never stretched). North is up.
///
/// The source: RGB, a TiledSource (256-texel tiles, a 256 MiB cache) whose level 0 is the frame
/// times 2^kVectorMapDetail (scale = 8) and whose levels are each drawn by cairo at their own
/// resolution when a render first needs a tile (culled to the features whose bounding box meets
/// the tile): the background, then layer after layer those of its features it selects, if the
/// level's zoom is in the layer's range: polygons filled (even-odd, so holes stay open) and
/// outlined, lines stroked (round joins and caps), points drawn as dots, widths and radii in
/// the level's texels (see MapLayerStyle); so level_band is 0.25, lest two widths show where two
/// levels blend. Thread-safe: tiles share only read-only data.
///
/// The points of a layer with a label are not drawn into the texture but by SourceFile::overlay,
/// as upright dots of `radius` screen pixels at their mapped positions (draw_dots; shown where
/// the local scale is in the layer's zoom range), which then places and draws the labels of the
/// style's labelled layers (place_labels, draw_labels): so a lens that compresses the context
/// does not squash them; SourceFile::counters: "tiles" (drawn so far), "cache_peak_mb",
/// "labels" (placed on the last output), "features".
/// Throws InvalidInput naming "vector_map_source" for a size outside [0, 16384], data with a
/// vector_data_problem, a position outside [-180, 180] x [-90, 90] (naming its feature: pixel
/// coordinates are not a map), or nothing to frame (no coordinates and no extent).
SourceFile vector_map_source(const VectorData& data, const MapStyle& style, int width = 0,
                             int height = 0);

/// The labels vector_map_source(data, style, width, height) places through its overlay, with
/// their positions in frame pixels (for a caller that places them itself, or counts what shows).
/// Throws as vector_map_source, naming "vector_map_labels".
std::vector<MapLabel> vector_map_labels(const VectorData& data, const MapStyle& style,
                                        int width = 0, int height = 0);

/// vector_map_source of the GeoJSON file at `path` (read_geojson) in the style file
/// options.style (read_map_style; empty: default_map_style()), framed options.width x
/// options.height. Throws InvalidInput naming the file at fault and the element (parse_geojson)
/// or key (parse_map_style).
SourceFile open_vector_map(const std::string& path, const SourceFileOptions& options = {});

}  // namespace geolens
