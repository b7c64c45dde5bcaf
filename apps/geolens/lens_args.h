#pragma once
// The lens options shared by every geolens subcommand that places lenses.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "geolens/io/image.h"
#include "geolens/lens/geometric_lens.h"

namespace geolens::cli {

/// The raw command-line values; parse() turns them into lenses and options.
struct LensArgs {
  std::vector<std::string> lenses;
  double zoom = 2.0;
  std::string profile = "gaussian", metric = "paper", weights = "paper", texture = "cotan",
              model = "focus", boundary = "sliding", extent = "global";
  double alpha = 0.0, tolerance = 1e-3, extent_factor = 2.5, footprint = 0;
  int mesh = 100, max_iterations = 100, subdivide = 0;
};

/// Registers --lens (required), --zoom, --model, --footprint, --profile, --mesh, --subdivide,
/// --metric, --alpha, --weights, --texture, --boundary, --extent, --extent-factor, --tolerance
/// and --max-iterations on `command`.
void add_lens_options(CLI::App& command, LensArgs& args);

/// The solver options; throws InvalidInput for an unknown name or a value out of range.
LensOptions parse_options(const LensArgs& args);

/// The lenses, validated against `source`: `circle:CX,CY,R[:ZOOM]` (source pixels),
/// `polygon:FILE[:ZOOM]`, `mask:FILE[:ZOOM]` (a PNG of the source's size; each 8-connected blob
/// of non-zero pixels is one lens).
/// Throws InvalidInput naming the offending --lens value.
std::vector<Lens> parse_lenses(const LensArgs& args, const Image& source);

/// Prints a warning on stderr for each lens that does not fit where it is (the largest zoom
/// that fits, for the focus model) or misses its requested zoom by more than 10 %.
void warn_about_zooms(const std::vector<Lens>& lenses, const LensResult& result);

}  // namespace geolens::cli
