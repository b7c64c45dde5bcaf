#pragma once
// The statistics of one magnify run, as the CLI's --stats writes them (and the viewer and
// Python next): JSON text.

#include <string>
#include <utility>
#include <vector>

#include "geolens/lens/geometric_lens.h"
#include "geolens/measure/distortion.h"

namespace geolens {

/// Wall-clock milliseconds of the parts of a run around the solve (whose own stages are in
/// LensResult::timings): reading the input and the lenses, measuring the result, rendering,
/// writing the outputs, and the whole run.
struct RunTimings {
  ///@{
  double load = 0, measure = 0, render = 0, save = 0, total = 0;  ///< milliseconds, as above
  ///@}
};

/// What a run read its source from (source/source_file.h's SourceFile, without the source).
struct RunSource {
  std::string kind;  ///< "image", "tiles", "svg", ...; "" = not reported
  ///@{
  int frame_width = 0, frame_height = 0;  ///< SourceFile's frame, pixels; reported as `frame`
  ///@}
  double scale = 1;  ///< texels of the source's finest level per frame pixel
  std::vector<std::pair<std::string, double>> counters;  ///< SourceFile::counters after the render
};

/// Everything a user needs to judge one run, as a JSON object (2-space indented, newline at the
/// end): mesh size, convergence, flips, the options the model read (reads_option; per lens its
/// profile or footprint likewise), per lens the requested and measured zoom and
/// the focus measures (measure_foci), the distortion summary, and `timings_ms`: `load`, `lift`,
/// `texture`, `factorize`, `iterate`, `solve` (the whole solve, those four included), `measure`,
/// `render`, `save`, `other` (argument parsing and checks: total less the rest, >= 0) and
/// `total` = load + solve + measure + render + save + other; and, when source.kind is not empty,
/// `source`: `kind`, `frame` [width, height], `scale` and each of its counters by name.
std::string run_stats_json(const std::vector<Lens>& lenses, const LensOptions& options,
                           const LensResult& result, const DistortionSummary& distortion,
                           const RunTimings& timings, const RunSource& source = {});

}  // namespace geolens
