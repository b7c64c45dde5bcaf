#pragma once
// `geolens map`: vector data (CSV points, GeoJSON) mapped through the lens, both ways; and what
// `magnify --overlay` shares with it.

#include <CLI/CLI.hpp>
#include <string>

#include "geolens/warp/map_features.h"
#include "geolens/warp/warp_map.h"
#include "geolens/warp/warp_mesh.h"
#include "lens_args.h"

namespace geolens {

struct MapArgs {
  std::string input;     ///< a CSV or GeoJSON file, or "-" for standard input
  std::string output;    ///< the file written; "" (or "-") for standard output
  std::string image;     ///< the source image the lenses are placed on (its size is used)
  std::string style;     ///< the style file of an --image vector map
  std::string size;      ///< WxH: the output size; without --image also the source's
  std::string format;    ///< csv or geojson; "" = from the input's (or output's) extension
  bool inverse = false;  ///< screen -> source instead of source -> screen
  double max_segment = MapOptions{}.max_segment;  ///< densify lines and rings, input pixels
  std::string max_points;  ///< --max-points N, a CSV or GeoJSON input's; "" = kMaxCsvPoints
  cli::LensArgs lens;      ///< the same lens options as `magnify`
};

/// Registers the `map` subcommand and its options on `app`.
CLI::App* add_map_command(CLI::App& app, MapArgs& args);

/// Solves the lenses on the source (its size from --image, else --size), frames the warp at the
/// output size (--size, else the source's), maps the input through it (map_features or
/// map_points, warp/map_features.h) and writes the result in the input's format to --output or
/// standard output, nothing on error. Returns the exit code; throws InvalidInput for bad input
/// (an unknown format, an input that does not parse, an output that is an input) before the
/// lenses are solved.
int run_map(const MapArgs& args);

/// Prints one warning line on stderr if `losses` dropped or cut anything: `what` ("the overlay")
/// is partly outside `area` ("the source image"), with the counts.
void warn_about_losses(const MapLosses& losses, const std::string& what, const std::string& area);

}  // namespace geolens
