#pragma once
// The source options shared by every geolens subcommand that reads a source: the input may be an
// image or any source file open_source reads (source/source_file.h).

#include <CLI/CLI.hpp>
#include <string>
#include <utility>

#include "geolens/io/run_files.h"
#include "geolens/source/source_file.h"

namespace geolens::cli {

/// The raw command-line values of the source options.
struct SourceArgs {
  std::string size;          ///< --size WxH; "" = the source's frame
  std::string style;         ///< --style FILE, a vector map's
  std::string view;          ///< --view AZ,EL, a 3D scene's camera
  std::string transfer;      ///< --transfer NAME|FILE, a volume's
  std::string max_pixels;    ///< --max-pixels N, an image's; "" = kMaxImagePixels
  std::string max_voxels;    ///< --max-voxels N, a volume's; "" = the readers' default (2^28)
  std::string max_vertices;  ///< --max-vertices N, a 3D mesh's; "" = the readers' default (2^22)
  std::string max_points;    ///< --max-points N, a GeoJSON input's; "" = kMaxGeoJsonPoints
};

/// Registers --size (described by `size_help`), --style, --view, --transfer, --max-pixels,
/// --max-voxels, --max-vertices and --max-points on `command`.
void add_source_options(CLI::App& command, SourceArgs& args, const std::string& size_help);

/// Adds the input and the --style file (if any) to `files` as inputs, so no output overwrites
/// them.
void add_source_inputs(RunFiles& files, const std::string& input, const SourceArgs& args);

/// Opens `input` with open_source: --size frames a source without pixels of its own and picks
/// a pyramid's level; --style, --view and --transfer go to the kinds that take them. Throws
/// InvalidInput for a bad --size or a source that cannot be read.
SourceFile open_input(const std::string& input, const SourceArgs& args);

/// --max-points as a number, kMaxGeoJsonPoints if not given. Throws InvalidInput naming the
/// option for a value that is not a whole number in [1, 2^30].
size_t max_points(const SourceArgs& args);

/// The output size: --size, else the source's frame.
std::pair<int, int> output_size(const SourceFile& file, const SourceArgs& args);

}  // namespace geolens::cli
