#include "source/mesh_source.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>

#include "geolens/core/errors.h"
#include "render3d/obj_file.h"
#include "render3d/ply_file.h"
#include "source/scene_tiles.h"

namespace geolens {

SourceFile mesh_source(TriangleMesh mesh, int frame_width, int frame_height,
                       const MeshSourceOptions& options) {
  auto renderer = std::make_shared<const MeshRenderer>(std::move(mesh), options.camera, frame_width,
                                                       frame_height, options.style);
  return scene_source([renderer](const PixelRegion& region) { return renderer->render(region); },
                      frame_width, frame_height, options.detail_levels, options.tiling, "mesh");
}

SourceFile open_mesh_source(const std::string& path, const SourceFileOptions& options,
                            const MeshSourceOptions& mesh) {
  const char* f = "open_mesh_source";
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  require(ext == ".obj" || ext == ".ply", f,
          "'" + path + "' is not a mesh file (expected .obj or .ply)");
  require(
      (options.width == 0) == (options.height == 0) && options.width >= 0 && options.height >= 0, f,
      "'" + path + "': size " + std::to_string(options.width) + " x " +
          std::to_string(options.height) + " has an empty side");
  MeshSourceOptions chosen = mesh;
  try {
    parse_view(options.view, chosen.camera);
  } catch (const InvalidInput& e) {
    throw InvalidInput(std::string(f) + ": '" + path + "': " + e.what());
  }
  const int width = options.width == 0 ? 1024 : options.width;
  const int height = options.height == 0 ? 1024 : options.height;
  const size_t max_vertices =
      options.max_vertices > 0 ? size_t(options.max_vertices) : kMaxMeshVertices;
  TriangleMesh loaded = ext == ".obj" ? load_obj(path, max_vertices) : load_ply(path, max_vertices);
  return mesh_source(std::move(loaded), width, height, chosen);
}

}  // namespace geolens
