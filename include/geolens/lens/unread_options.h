#pragma once
// The options a lens model does not read: what every face warns about and leaves out of its
// stats, so that none echoes a setting as if it had been used.

#include <string>
#include <vector>

#include "geolens/lens/geometric_lens.h"

namespace geolens {

/// An option set away from its default that the model solving the lenses does not read.
struct UnreadOption {
  /// The option as the faces name it, words joined by '_' (the CLI writes "--mesh-tolerance",
  /// Python mesh_tolerance=): "profile", "footprint", "mesh_tolerance", "subdivide", "extent",
  /// "extent_factor", "texture", "weights", "metric", "alpha" or "boundary".
  std::string name;
  std::string reason;  ///< why it is not read, e.g. "only the lift model re-maps the texture"
};

/// The options of `options`, and the lenses' profiles and footprints, that differ from their
/// defaults (LensOptions{}, Lens{}) and that the model solving `lenses` (options.model, kAuto
/// resolved) does not read, in the order listed above. Some are read only with another option:
/// extent_factor with the local extent, metric with alpha > 0 (at 0 both metrics are
/// as-rigid-as-possible). Read by every model, and so never listed: mesh, model, tolerance,
/// max_iterations, threads and the lenses' zooms.
std::vector<UnreadOption> unread_options(const LensOptions& options,
                                         const std::vector<Lens>& lenses);

/// Whether the model solving `lenses` with `options` reads the option `name` (named as above;
/// true for any other name): what a face's stats echo.
bool reads_option(const LensOptions& options, const std::vector<Lens>& lenses,
                  const std::string& name);

}  // namespace geolens
