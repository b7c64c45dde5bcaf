#pragma once
// A source opened from a file by its type: an image, an image pyramid, a folder of web-map tiles,
// an SVG, a vector map, a 3D mesh or volume. What the command line and the viewer take wherever
// they take an image.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geolens/io/geojson.h"
#include "geolens/io/image.h"
#include "geolens/source/map_style.h"
#include "geolens/source/source.h"
#include "geolens/warp/warp_map.h"

namespace geolens {

class WarpMap;  // warp/warp_map.h

/// What to open a source file with; each field only matters to the kinds that name it.
struct SourceFileOptions {
  /// The frame, pixels (--size): for a source without pixels of its own (SVG, vector map, 3D
  /// scene) the whole extent drawn at this size is the frame at zoom 1; for a pyramid or a tile
  /// folder the level nearest this size is. 0 x 0: the kind's own default.
  ///@{
  int width = 0, height = 0;
  ///@}
  std::string style;     ///< vector map: a style file (--style); empty: the built-in style
  std::string view;      ///< 3D scene: the camera (--view), e.g. "AZ,EL" in degrees
  std::string transfer;  ///< volume: a transfer preset or table file (--transfer)
  uint64_t max_pixels = kMaxImagePixels;  ///< image: the most pixels decoded (--max-pixels), >= 1
  /// volume (NIfTI, NRRD): the most voxels read (--max-voxels), >= 1; 0: the readers' default,
  /// 2^28 (render3d's kMaxVoxels, not an installed header)
  uint64_t max_voxels = 0;
  /// 3D mesh (OBJ, PLY): the most vertices read (--max-vertices), >= 1; 0: the readers' default,
  /// 2^22 (render3d's kMaxMeshVertices)
  uint64_t max_vertices = 0;
  /// vector map (GeoJSON): the most positions read (--max-points), >= 1
  uint64_t max_points = kMaxGeoJsonPoints;
};

/// A source opened from a file, and the frame lenses are placed in. Lenses, the solved mesh's
/// source coordinates and the default output size are in frame pixels; `source` may be finer, so
/// that a magnified focus shows real detail: its level 0 has `scale` texels per frame pixel, and a
/// render passes RenderOptions::source_scale = scale (the renderer then picks, per triangle, the
/// level the magnification needs, and blends neighbouring levels).
struct SourceFile {
  std::shared_ptr<const Source> source;  ///< never null
  ///@{
  int frame_width = 0, frame_height = 0;  ///< the frame, pixels, >= 1
  ///@}
  double scale = 1;  ///< > 0; 1 for a plain image
  /// RenderOptions::level_band to render it with: 1 (trilinear) where a level is the same picture
  /// at another resolution; narrower where each level is drawn on its own (a web map's tiles, a
  /// vector map), whose labels and line widths would otherwise show twice where levels blend.
  double level_band = 1;
  std::string kind;  ///< "image", "level list", "tiles", "svg", ...
  /// Numbers a run reports in --stats after rendering (e.g. {"missing_tiles", 3}); may be empty.
  std::function<std::vector<std::pair<std::string, double>>()> counters;
  /// Drawn over an output after rendering, in its pixels, given the warp it was rendered through
  /// framed at its size (framed_warp_map, warp/warp_map.h): what must stay upright and unwarped,
  /// such as a vector map's labels. May be empty; the output is RGB or RGBA.
  std::function<void(Image& output, const WarpMap& map)> overlay;
  /// A vector map's: where longitude and latitude lie in the frame (map_style.h), so data in
  /// degrees can be placed on it; empty for every other kind.
  std::optional<MapFrame> map_frame;
};

/// A plain image as a SourceFile: its mip pyramid, framed at its size, scale 1.
SourceFile image_source(const Image& image);

/// Opens `path` by its type: a folder of z/x/y.png tiles, a level list (.levels), an SVG (.svg),
/// a vector map (.geojson, .json), a mesh (.obj, .ply), a volume (.nii, .nii.gz, .nrrd); anything
/// else as an image (PNG or JPEG by content). Throws InvalidInput naming the file and, where it
/// can, the element or line at fault.
SourceFile open_source(const std::string& path, const SourceFileOptions& options = {});

/// The files open_source(path) reads besides `path` itself, found without decoding anything: a
/// level list's images (level_list_images), a NRRD's detached data file (nrrd_data_path); none
/// for other kinds (a tile folder is a folder: every file in it is read). For the checks a tool
/// makes before its work, so that no output overwrites one of them.
std::vector<std::string> source_parts(const std::string& path);

}  // namespace geolens
