#pragma once
// What a geometric lens can be asked: the model, its mesh and extent, and the options of the
// paper's steps (subdivision, texture map, flattening), with their names as the faces spell them
// (parse_* and to_string) and their checks (validate); and what a flattening reports.

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "geolens/geometry/subdivide.h"
#include "geolens/lens/lens.h"

namespace geolens {

/// Per-edge weights of the global step.
enum class FlattenWeights {
  kPaper,  ///< (1 + h_m) A_m cot(theta): h_m the triangle's mean normalized height (level in
           ///< [0, 1]), A_m its 3D area over the mean planar area
  kCotan,  ///< cot(theta): the plain ARAP energy
};

/// The target transformation each triangle is fitted to in the local step, from the signed
/// SVD J = U diag(s1, s2) V^T of the triangle's current Jacobian (standard -> current).
enum class Metric {
  /// The paper's Eq. 6: U diag(alpha (s1 - 1) + 1, alpha (s2 - 1) + 1) V^T. Equal to
  /// (1 - alpha) R + alpha J, so it is a damped ARAP step with the ARAP fixed point for every
  /// alpha < 1: it differs from ARAP only when stopped early (DESIGN decision 1).
  kPaper,
  /// A spectrum that keeps its effect at convergence: b U V^T with
  /// b = (1 - alpha) + alpha (s1 + s2) / 2; alpha = 0 is rigid (ARAP), alpha = 1 the closest
  /// similarity (ASAP, angle-preserving), after Liu et al. 2008.
  kSpectrum,
};

/// The shape each triangle is asked to keep (its "standard triangle").
enum class Standard {
  kLifted,  ///< the lifted 3D triangle laid flat isometrically (paper Fig. 4)
  /// the planar triangle scaled by exp of the mean `log_scale` of its corners: a prescribed
  /// isotropic magnification (LensModel::kField)
  kScaled,
};

/// Which image-border conditions the flattened mesh obeys.
enum class Boundary {
  kSliding,  ///< border vertices slide along their own side, corners fixed
  kFixed,    ///< border vertices pinned where they were
  kFree,     ///< one vertex pinned (translation); the result is later scaled to fit
};

FlattenWeights parse_flatten_weights(const std::string& name);  ///< "paper" | "cotan"
Metric parse_metric(const std::string& name);                   ///< "paper" | "spectrum"
Boundary parse_boundary(const std::string& name);               ///< "sliding" | "fixed" | "free"
std::string to_string(FlattenWeights weights);  ///< the name parse_flatten_weights reads
std::string to_string(Metric metric);           ///< the name parse_metric reads
std::string to_string(Boundary boundary);       ///< the name parse_boundary reads

/// How the local/global flattener (paper 5) solves: its weights, metric, boundary and stopping
/// rule.
struct FlattenOptions {
  FlattenWeights weights = FlattenWeights::kPaper;  ///< per-edge weights of the global step
  Metric metric = Metric::kPaper;  ///< the local step's target metric (with `alpha`)
  double alpha = 0.0;  ///< metric blend: [0, 1) for kPaper (the paper uses [0, 0.5]), [0, 1]
                       ///< for kSpectrum
  Boundary boundary = Boundary::kSliding;  ///< what the image's border vertices may do
  Standard standard = Standard::kLifted;   ///< the shapes the local step keeps
  double tolerance = 1e-3;   ///< stop when |E_k - E_k-1| <= tolerance * E_k-1 (paper: 0.1%)
  int max_iterations = 100;  ///< cap on global steps, >= 1
  /// Bound each step so no triangle changes orientation: the global step's result X' is taken
  /// as X + s (X' - X) with s = min(1, 0.9 s_max), s_max the first s at which a triangle of the
  /// current (flip-free) flattening would degenerate (after Smith and Schaefer 2015's
  /// flip-preventing line search). The energy still never increases.
  bool flip_safe = true;
  /// Threads of the flattener's pool (the per-triangle steps, the x and y factorizations), the
  /// calling thread included: 0 = one per hardware thread, 1 = the calling thread only, >= 0.
  /// Results do not depend on it.
  int threads = 0;
};

/// Throws InvalidInput unless the options are in range.
void validate(const FlattenOptions& options);

/// Edge weights of the discrete harmonic map, both computed on the 3D mesh.
enum class TextureWeights {
  kMeanValue,  ///< Floater 2003 mean value weights, the paper's choice; not symmetric
  kCotan,      ///< cotangent weights (Pinkall-Polthier), symmetric; negative on obtuse angles
  /// cotangent weights with negative ones set to 0: every weight >= 0, so (Tutte, Floater) the
  /// map cannot fold where the fixed ring is convex; more distortion than kCotan at low zoom
  kPositiveCotan,
};

TextureWeights parse_texture_weights(const std::string& name);  ///< "mvc" | "cotan" | "cotan+"
std::string to_string(TextureWeights weights);  ///< the name parse_texture_weights reads

/// Which part of the image takes part in the solve.
enum class Extent {
  kGlobal,  ///< the whole image: the context everywhere gives way to the lens
  /// a square patch of side 2 * extent_factor * size around the lenses (clipped to the image),
  /// its border pinned; the rest of the image is the identity. The patch grid has `mesh`
  /// vertices along its long side whatever the image size, so the cost depends on the lens.
  kLocal,
};
Extent parse_extent(const std::string& name);  ///< "global" | "local"
std::string to_string(Extent extent);          ///< the name parse_extent reads

/// What a lens magnifies and how (docs/design.md, "Focus lenses" and "Lens models").
enum class LensModel {
  /// The region is the focus: magnified as a whole by its zoom (a similarity, translated to fit
  /// but not rotated), the context giving way within the lens's footprint, with its shape
  /// distortion bounded, and unchanged beyond (focus_lens.h). The solved area is the footprints'
  /// bounding box, so the mesh moves with the lens.
  kFocus,
  /// The paper's: the flattening keeps the shapes of the lifted triangles and the texture is
  /// re-mapped harmonically onto the bump. A long region's lift is a ridge, magnified across
  /// only.
  kLift,
  /// The lift read as a field of log magnification (Lifted::log_zoom): the flattening keeps
  /// each planar triangle's shape scaled by it, the texture is not re-mapped. A region of any
  /// shape reaches its zoom at its peak, junctions included; a thinner part asks for less
  /// (log zoom grows with the local half-width), and a long thin arm still widens more than
  /// it lengthens.
  kField,
  kAuto,  ///< kLift when every lens is a circle, else kField
};
LensModel parse_lens_model(const std::string& name);  ///< "focus" | "lift" | "field" | "auto"
std::string to_string(LensModel model);               ///< the name parse_lens_model reads
/// The model that solves `lenses` with `model` asked: kAuto resolved, any other as it is.
LensModel resolved_model(LensModel model, const std::vector<Lens>& lenses);

/// Everything a GeometricLens (and a LensSession) is built with: the model, its mesh and extent,
/// and the options of the paper's steps. Checked by validate(); the defaults are what every face
/// starts from.
struct LensOptions {
  int mesh = 100;  ///< grid vertices along the solved area's long side, in [4, 1000]
  /// kFocus: the grid is refined where the lens's start (focus_start) strays from linear over a
  /// triangle by more than this, output pixels, or than 1/400 of the smallest region's reach
  /// (>= 0; 0: not refined). A draft (LensSession) is not refined.
  double mesh_tolerance = 0.2;
  /// LensSession's drafts (a drag's frames) on a grid of this many vertices along the long side
  /// instead of `mesh` (0: `mesh`; else in [4, 1000]).
  int draft_mesh = 0;
  Extent extent = Extent::kGlobal;      ///< kLift and kField only (kFocus solves its footprints)
  double extent_factor = 2.5;           ///< local patch half-side over the lens size (radius), > 1
  LensModel model = LensModel::kFocus;  ///< how the lenses are solved
  TextureWeights texture = TextureWeights::kCotan;  ///< kLift and kField: the texture map's weights
  SubdivisionOptions subdivision;  ///< kLift and kField: where the lifted mesh is refined
  FlattenOptions flatten;          ///< the flattener's options, every model
  /// kLift and kField: bump heights are calibrated until every lens's measured zoom is within
  /// this relative tolerance of its request, or `max_calibration_solves` full solves were made.
  double zoom_tolerance = 0.02;
  int max_calibration_solves = 12;  ///< kLift and kField: full solves at most, >= 1
};

/// Throws InvalidInput unless the options are in range.
void validate(const LensOptions& options);

/// One setting of LensOptions as every face names, shows and sets it (the CLI's
/// --mesh-tolerance, Python's mesh_tolerance=, the viewer's --mesh): the faces bind this table,
/// so none lists the options, their defaults or their help again.
struct LensOptionField {
  /// What the text of a value is.
  enum class Type {
    kInteger,  ///< decimal digits (read_integer, core/parse.h)
    kNumber,   ///< a finite number (read_number)
    kChoice,   ///< one of `choices`
  };
  std::string name;           ///< words joined by '_', as InvalidOption and unread_options name it
  Type type = Type::kNumber;  ///< what its text is
  std::string help;  ///< one line: what it sets, its range or its choices, the models reading it
  std::vector<std::string> choices;  ///< kChoice: the names it takes
  /// The value in `options` as text: an integer, a number that reads back to it (number_text,
  /// core/errors.h) or a choice's name.
  std::function<std::string(const LensOptions&)> get;
  /// Sets the value in `options` from text as `get` writes it; throws InvalidOption naming the
  /// field for text that does not read ("must be an integer, got '2.5'"). Its range is
  /// validate()'s.
  std::function<void(LensOptions&, const std::string&)> set;
};

/// Every field, in the order the faces list them: model, mesh, mesh_tolerance, draft_mesh,
/// subdivide, metric, alpha, weights, texture, boundary, extent, extent_factor, tolerance,
/// max_iterations, threads. Built once; safe to read from any thread.
const std::vector<LensOptionField>& lens_option_fields();
/// The field named `name`; throws InvalidInput listing the fields for any other name.
const LensOptionField& lens_option_field(const std::string& name);
/// `name` as the command-line faces spell it: "mesh_tolerance" -> "--mesh-tolerance".
std::string option_flag(const std::string& name);

/// What one flattening (the final solve of a GeometricLens) reports.
struct FlattenResult {
  Eigen::MatrixX2d X;          ///< #V x 2 flattened positions, pixels (before framing)
  std::vector<double> energy;  ///< energy of the initial guess, then after each global step
  int iterations = 0;          ///< global steps taken
  int bounded_steps = 0;       ///< steps the flip-safe bound shortened
  bool converged = false;      ///< the tolerance was met before the cap
};

// The options a lens model does not read: what every face warns about and leaves out of its
// stats, so that none echoes a setting as if it had been used.

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
