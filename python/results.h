#pragma once
// What the lenses return to Python: the warp, indexed for point queries, and per lens what was
// asked and what was built; the geometric lens's result adds how it was solved and its stats.

#include <pybind11/pybind11.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens.h"
#include "geolens/warp/warp_map.h"

namespace geolens::python {

namespace py = pybind11;

/// Magnification (lens/lens.h) with its warp as a WarpMap, which owns the mesh and
/// maps points through it.
struct MagnificationResult {
  explicit MagnificationResult(Magnification magnification);
  std::shared_ptr<WarpMap> warp;
  std::vector<double> zoom_parameter, zoom_measured;
  bool draft = false;
};

/// GeometricLens::solve's or LensSession::update's result, with the lenses and options it was
/// solved for, from which its stats are made (run_stats_json, eval/run_stats.h).
struct LensSolveResult : MagnificationResult {
  LensSolveResult(LensResult result, std::vector<Lens> lenses, const LensOptions& options);
  /// The stats as --stats writes them (timings: the solve's, and `measure` for the stats'
  /// own measures), made on first use.
  const std::string& stats_json() const;

  LensResult result;  // its warp a copy of the WarpMap's, as run_stats_json reads it there
  std::vector<Lens> lenses;
  LensOptions options;

 private:
  mutable std::optional<std::string> stats_;
};

/// A JSON text (the library's reports) as Python objects (json.loads).
py::object parse_json(const std::string& text);

/// Registers Warp, Magnification, LensResult and GeometricLens on `module`.
void bind_results(py::module_& module);

}  // namespace geolens::python
