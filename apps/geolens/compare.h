#pragma once
// `geolens compare`: the geometric lens next to the classic lenses, measured the same way.

#include <CLI/CLI.hpp>
#include <string>

#include "lens_args.h"
#include "source_args.h"

namespace geolens {

struct CompareArgs {
  std::string input, output;   ///< input image or source file; output folder
  cli::SourceArgs source;      ///< --size (the frame of a source without pixels), --style, ...
  cli::LensArgs lens;          ///< the same lens options as `magnify`
  std::string format = "png";  ///< image files written: png or jpg
  int jpeg_quality = 92;       ///< JPEG quality for format jpg, in [1, 100]
  int tile = 256;              ///< panel tile side, pixels, in [64, 1024]
  int baseline_mesh = 200;     ///< classic lens grid vertices along the long side, [4, 1000]
  double heat_max = 0;         ///< distortion shown red; 0 = the largest over all methods
  bool sweep = false;          ///< the footprint sweep instead of the comparison
};

/// Registers the `compare` subcommand and its options on `app`.
CLI::App* add_compare_command(CLI::App& app, CompareArgs& args);

/// Compares the geometric lens with the seven classic lenses matched to its measured zoom
/// (compare_lenses, eval/comparison.h: circle lenses only; against a focus lens, with its footprint
/// as radius and a flat top of its region's size) and writes into the output folder, per method
/// NAME (geometric, zoom_in, fisheye, fisheye_smooth, bifocal, flattop_linear, flattop_cosine,
/// power_ring): NAME.FORMAT (the output) and NAME_heatmap.FORMAT (its shape distortion with a
/// scale), then panel.FORMAT (every method side by side around the lenses, labelled), report.json
/// and report.md. With --sweep, one lens's footprint sweep instead (comparison.h): sweep.json,
/// sweep.md and sweep.FORMAT. Returns the exit code; throws InvalidInput for bad input (an output
/// file that is a folder or an input among it) before any work, and renames the files into place
/// only once all are written.
int run_compare(const CompareArgs& args);

}  // namespace geolens
