#pragma once
// A triangle mesh (OBJ, PLY) as a source: the view of a camera, rendered per tile and level
// of detail, so a magnified focus is a real render at its zoom.

#include <string>

#include "geolens/source/source.h"
#include "geolens/source/source_file.h"
#include "render3d/mesh_renderer.h"

namespace geolens {

struct MeshSourceOptions {
  OrbitCamera camera;  ///< default: azimuth 30, elevation 20, fitted, 30 degrees, +Y up
  MeshStyle style;     ///< default: smooth, no edges, 2 x 2 samples per texel
  /// k: level 0 has 2^k texels per frame pixel (SourceFile::scale), in [0, 4]; a lens of zoom
  /// up to 2^k is drawn from a render at least as fine as it shows.
  int detail_levels = 2;
  TiledSourceOptions tiling;  ///< tile size and cache budget
};

/// `mesh` seen by options.camera in a frame_width x frame_height frame, as a SourceFile of kind
/// "mesh" (source/scene_tiles.h scene_source over a MeshRenderer). Throws InvalidInput naming
/// "MeshRenderer" or "scene_source" for an invalid mesh, camera, style, frame or tiling.
SourceFile mesh_source(TriangleMesh mesh, int frame_width, int frame_height,
                       const MeshSourceOptions& options = {});

/// Opens an OBJ (load_obj) or PLY (load_ply) file by its extension as mesh_source(): the frame
/// is options.width x options.height (0 x 0: 1024 x 1024), the view options.view ("AZ,EL",
/// parse_view; empty: 30,20), the rest `mesh` (its camera's azimuth and elevation replaced by
/// the view). Throws InvalidInput naming "open_mesh_source" and the file for another extension,
/// a frame with one side 0, and what the readers and mesh_source refuse.
SourceFile open_mesh_source(const std::string& path, const SourceFileOptions& options,
                            const MeshSourceOptions& mesh = {});

}  // namespace geolens
