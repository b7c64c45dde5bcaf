#include "source_args.h"

#include <filesystem>

#include "lens_args.h"

namespace geolens::cli {

void add_source_options(CLI::App& command, SourceArgs& a, const std::string& size_help) {
  command.add_option("--size", a.size, size_help);
  command.add_option("--style", a.style, "style file (JSON) of a vector map input");
  command.add_option("--view", a.view, "camera of a 3D input: AZ,EL in degrees");
  command.add_option("--transfer", a.transfer,
                     "transfer function of a volume input: a preset (ct, mri) or a table file");
  command.add_option("--max-pixels", a.max_pixels,
                     "the most pixels an image input may have (refused from its header above it; "
                     "each takes 4 bytes or more), in [1, 2^40]; default " +
                         std::to_string(kMaxImagePixels) + " (2^28)");
  command.add_option("--max-voxels", a.max_voxels,
                     "the most voxels a volume input (NIfTI, NRRD) may have (refused from its "
                     "header above it; each takes 4 bytes), in [1, 2^36]; default 268435456 "
                     "(2^28)");
  command.add_option("--max-vertices", a.max_vertices,
                     "the most vertices a 3D mesh input (OBJ, PLY) may have (a file of more than "
                     "128 bytes a vertex is refused unread), in [1, 2^34]; default 4194304 (2^22)");
  command.add_option("--max-points", a.max_points,
                     "the most positions a GeoJSON input (a vector map, --overlay) may hold (a "
                     "file of more than 16 bytes a position is refused unread), in [1, 2^30]; "
                     "default " +
                         std::to_string(kMaxGeoJsonPoints) + " (2^22)");
}

void add_source_inputs(RunFiles& files, const std::string& input, const SourceArgs& a) {
  files.add_input("the input", input);
  // A tile folder's tiles, a pyramid's level images and a volume's detached data are inputs too.
  if (std::filesystem::is_directory(input)) files.add_input_folder("the input tile folder", input);
  for (const std::string& part : source_parts(input))
    files.add_input("part of the input '" + input + "'", part);
  if (!a.style.empty()) files.add_input("the --style file", a.style);
  // A --transfer that names a file is read too; a preset name is no file and clashes with none.
  if (!a.transfer.empty()) files.add_input("the --transfer file", a.transfer);
}

SourceFile open_input(const std::string& input, const SourceArgs& a) {
  SourceFileOptions options;
  if (!a.size.empty())
    std::tie(options.width, options.height) = parse_size(a.size, "--size", 1, kMaxSide);
  options.style = a.style;
  options.view = a.view;
  options.transfer = a.transfer;
  if (!a.max_pixels.empty())
    options.max_pixels = parse_count(a.max_pixels, "--max-pixels", 1, uint64_t(1) << 40);
  if (!a.max_voxels.empty())
    options.max_voxels = parse_count(a.max_voxels, "--max-voxels", 1, uint64_t(1) << 36);
  if (!a.max_vertices.empty())
    options.max_vertices = parse_count(a.max_vertices, "--max-vertices", 1, uint64_t(1) << 34);
  options.max_points = max_points(a);
  return open_source(input, options);
}

size_t max_points(const SourceArgs& a) {
  return a.max_points.empty() ? kMaxGeoJsonPoints
                              : size_t(parse_count(a.max_points, "--max-points", 1, 1u << 30));
}

std::pair<int, int> output_size(const SourceFile& file, const SourceArgs& a) {
  return a.size.empty() ? std::pair{file.frame_width, file.frame_height}
                        : parse_size(a.size, "--size", 1, kMaxSide);
}

}  // namespace geolens::cli
