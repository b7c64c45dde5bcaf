#include "geolens/source/source_file.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "geolens/io/image.h"
#include "geolens/source/source.h"
#include "render3d/nrrd_file.h"
#include "source/level_list.h"
#include "source/mesh_source.h"
#include "source/svg_source.h"
#include "source/vector_map.h"
#include "source/volume_source.h"
#include "source/xyz_tiles.h"

namespace geolens {

namespace {

/// `path`'s extension in lower case, with its dot (".svg"); ".nii.gz" for a gzipped NIfTI.
std::string extension(const std::string& path) {
  std::string name = std::filesystem::path(path).filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (name.size() > 7 && name.compare(name.size() - 7, 7, ".nii.gz") == 0) return ".nii.gz";
  const size_t dot = name.rfind('.');
  return dot == std::string::npos ? std::string() : name.substr(dot);
}

}  // namespace

SourceFile image_source(const Image& image) {
  SourceFile file;
  file.source = std::make_shared<const MipPyramid>(image);
  file.frame_width = image.width;
  file.frame_height = image.height;
  file.kind = "image";
  return file;
}

std::vector<std::string> source_parts(const std::string& path) {
  const std::string ext = extension(path);
  if (ext == ".levels") return level_list_images(path);
  if (ext == ".nrrd")
    if (std::string data = nrrd_data_path(path); !data.empty()) return {data};
  return {};
}

SourceFile open_source(const std::string& path, const SourceFileOptions& options) {
  const std::string ext = extension(path);
  if (std::filesystem::is_directory(path)) return open_tile_folder(path, options);
  if (ext == ".levels") return open_level_list(path, options);
  if (ext == ".svg") return open_svg(path, options);
  if (ext == ".geojson" || ext == ".json") return open_vector_map(path, options);
  if (ext == ".obj" || ext == ".ply") return open_mesh_source(path, options);
  if (ext == ".nii" || ext == ".nii.gz" || ext == ".nrrd") return open_volume_source(path, options);
  return image_source(load_image(path, options.max_pixels));
}

}  // namespace geolens
