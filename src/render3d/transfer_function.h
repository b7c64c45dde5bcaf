#pragma once
// What a volume's values look like: colour and opacity as a function of the value (presets
// for CT and MRI, or a table file).

#include <array>
#include <string>
#include <vector>

#include "render3d/scalar_volume.h"

namespace geolens {

/// One control point: at `value` (the volume's units), colour (RGB in [0, 1]) and opacity in
/// [0, 1], the opacity of a slab one voxel thick (the volume's smallest spacing).
struct TransferPoint {
  double value = 0;
  std::array<double, 3> colour = {1, 1, 1};
  double opacity = 0;
};

/// Piecewise linear between control points, constant beyond the first and the last.
class TransferFunction {
 public:
  /// Throws InvalidInput naming "TransferFunction" unless there is at least one point, the
  /// values are finite and strictly increasing, and colours and opacities lie in [0, 1].
  explicit TransferFunction(std::vector<TransferPoint> points);

  /// RGB and opacity at `value`.
  std::array<double, 4> operator()(double value) const;
  const std::vector<TransferPoint>& points() const { return points_; }

 private:
  std::vector<TransferPoint> points_;
};

/// A preset: "ct" over Hounsfield units (air and fat clear, soft tissue a faint red, bone
/// opaque white from about 300 HU), or "mri" relative to the volume's 99th percentile p (below
/// 0.1 p clear, rising to an opaque white at p). Throws InvalidInput naming "transfer_preset"
/// and the name for another name.
TransferFunction transfer_preset(const std::string& name, const ScalarVolume& volume);

/// A table file: one control point per line, "VALUE R G B OPACITY" (R, G, B in [0, 255],
/// opacity in [0, 1]), values strictly increasing; blank lines and lines starting with '#'
/// skipped. Throws InvalidInput naming "load_transfer_table", the file and the line at fault.
TransferFunction load_transfer_table(const std::string& path);

/// What --transfer names: "ct" or "mri" (transfer_preset), else a table file (its path). Empty:
/// "ct" when the volume has values below -200 (Hounsfield units), else "mri". Throws
/// InvalidInput naming "transfer_function" for a name that is neither a preset nor a file.
TransferFunction transfer_function(const std::string& spec, const ScalarVolume& volume);

}  // namespace geolens
