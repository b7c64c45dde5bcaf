#include "geolens/lens/geometric_lens.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>

#include "geolens/core/errors.h"
#include "geolens/lens/classic_lens.h"
#include "geolens/lens/focus_lens.h"
#include "geolens/measure/distortion.h"

namespace geolens {

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kMaxHeightOverSize = 20.0;
// The field model's height over size is the peak's log zoom: at most 64x, the square of the
// largest zoom a lens may ask for (the context's resistance takes the rest).
const double kMaxFieldLogZoom = 2 * std::log(8.0);
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// First guess of the peak height for a zoom (pixels). The lift's, in units of the region's
// size, is a L + b L^2 with L = log(zoom), per profile (gaussian, sphere, mesa), fitted through
// the calibrated heights of zoom 2 and 3 (default options, 100 x 100 grid, r = 150 px on 1024
// px), so those need a single solve; the field's is its peak's log zoom, which the context's
// resistance lowers by about 1 / 1.7. L is taken at most log 8, where the fits still rise.
double height_for_zoom(const Lens& lens, LensModel model, double zoom) {
  if (model == LensModel::kFocus) return std::log(zoom);  // exact, up to the focus weight
  const double L = std::min(std::log(zoom), std::log(8.0));
  if (model == LensModel::kField) return lens.region.size() * 1.7 * L;
  const double a[] = {1.180, 2.854, 2.264}, b[] = {-0.0912, -0.687, -0.453};
  const int p = int(lens.profile);
  return lens.region.size() * (a[p] * L + b[p] * L * L);
}

// The first guess on a grid of cell side `cell` (pixels). The gaussian's peak is sharp, so a
// coarse grid under-represents its bump: the calibrated h0 / r for zoom 2 is 0.722 (cell / r
// below 0.035), 0.774 (0.069), 0.94 (0.138), about 1 + 15 (cell / r)^2 times the first, so the
// fit above (made at 0.069) is rescaled by that factor. The sphere and the mesa hardly change.
double initial_height(const Lens& lens, LensModel model, double cell) {
  const double h = height_for_zoom(lens, model, lens.zoom);
  if (model != LensModel::kLift || lens.profile != Profile::kGaussian) return h;
  auto coarseness = [](double x) { return 1 + 15 * x * x; };
  return h * coarseness(cell / lens.region.size()) / coarseness(0.069);
}

// The side of a grid cell over `box` with `mesh` vertices along its long side, pixels.
double cell_size(const Eigen::AlignedBox2d& box, int mesh) {
  return box.sizes().maxCoeff() / (mesh - 1);
}

// Scales the flattening to the frame: sliding and fixed borders already fill the image; a free
// flattening is scaled uniformly to fit and centred.
Eigen::MatrixX2d frame(const Eigen::MatrixX2d& X, Boundary boundary, double width, double height) {
  if (boundary != Boundary::kFree) return X;
  const Eigen::Vector2d lo = X.colwise().minCoeff(), hi = X.colwise().maxCoeff();
  const Eigen::Vector2d extent = hi - lo;
  const double scale = std::min(width / extent.x(), height / extent.y());
  const Eigen::RowVector2d offset(0.5 * (width - scale * extent.x()),
                                  0.5 * (height - scale * extent.y()));
  return ((X.rowwise() - lo.transpose()) * scale).rowwise() + offset;
}

// Triangulates the image rectangle outside the local patch `box` (whose border vertices are those
// of `mesh` with non-zero sides) as the identity, conforming to the patch border: four
// trapezoids, each fanned from its two outer corners. Appends to `warp`.
void add_identity_frame(WarpMesh& warp, const PlanarMesh& mesh, const Eigen::AlignedBox2d& box,
                        double width, double height) {
  const Eigen::Vector2d lo = box.min(), hi = box.max();
  // The four image corners are appended as identity vertices.
  const Eigen::Index first = warp.source.rows();
  const Eigen::Vector2d corner[4] = {{0, 0}, {width, 0}, {width, height}, {0, height}};
  warp.source.conservativeResize(first + 4, 2);
  warp.screen.conservativeResize(first + 4, 2);
  for (int k = 0; k < 4; ++k) {
    warp.source.row(first + k) = corner[k].transpose();
    warp.screen.row(first + k) = corner[k].transpose();
  }
  std::vector<Eigen::RowVector3i> faces;
  // Side k runs from patch corner k to k + 1 (top: left to right, right: top to bottom, ...),
  // facing image corners k and k + 1.
  const Eigen::Vector2d patch_corner[4] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d a = patch_corner[k], b = patch_corner[(k + 1) % 4];
    const Eigen::Vector2d direction = (b - a).normalized();
    // The trapezoid is empty where the patch touches the image side.
    const Eigen::Vector2d outward(direction.y(), -direction.x());
    if (std::abs((corner[k] - a).dot(outward)) < 1e-9) continue;
    std::vector<std::pair<double, int>> side;
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
      if (mesh.sides[size_t(i)] == 0) continue;
      const Eigen::Vector2d p = mesh.V.row(i);
      const Eigen::Vector2d d = p - a;
      if (std::abs(d.dot(outward)) < 1e-9 && d.dot(direction) > -1e-9 &&
          d.dot(direction) < (b - a).norm() + 1e-9)
        side.emplace_back(d.dot(direction), int(i));
    }
    std::sort(side.begin(), side.end());
    const int ca = int(first) + k, cb = int(first) + (k + 1) % 4;
    const size_t middle = side.size() / 2;
    // With y down, image corner -> patch side -> ... is oriented like the grid's triangles
    // when the patch side is walked from b back to a.
    for (size_t i = 0; i + 1 < side.size(); ++i) {
      const int apex = i < middle ? ca : cb;
      faces.emplace_back(apex, side[i + 1].second, side[i].second);
    }
    faces.emplace_back(ca, cb, side[middle].second);
  }
  const Eigen::Index old = warp.F.rows();
  warp.F.conservativeResize(old + Eigen::Index(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) warp.F.row(old + Eigen::Index(f)) = faces[f];
}

}  // namespace

Extent parse_extent(const std::string& name) {
  if (name == "global") return Extent::kGlobal;
  if (name == "local") return Extent::kLocal;
  throw InvalidInput("parse_extent: unknown extent '" + name + "' (expected global or local)");
}

std::string to_string(Extent extent) { return extent == Extent::kGlobal ? "global" : "local"; }

LensModel parse_lens_model(const std::string& name) {
  if (name == "focus") return LensModel::kFocus;
  if (name == "lift") return LensModel::kLift;
  if (name == "field") return LensModel::kField;
  if (name == "auto") return LensModel::kAuto;
  throw InvalidInput("parse_lens_model: unknown lens model '" + name +
                     "' (expected focus, lift, field or auto)");
}

std::string to_string(LensModel model) {
  switch (model) {
    case LensModel::kFocus:
      return "focus";
    case LensModel::kLift:
      return "lift";
    case LensModel::kField:
      return "field";
    case LensModel::kAuto:
      return "auto";
  }
  return "?";
}

void validate(const LensOptions& o) {
  require(std::isfinite(o.extent_factor) && o.extent_factor > 1 && o.extent_factor <= 100,
          "validate", "extent factor must be in (1, 100], got " + std::to_string(o.extent_factor));
  require_mesh_vertices(o.mesh, "validate");
  require(std::isfinite(o.zoom_tolerance) && o.zoom_tolerance > 0, "validate",
          "zoom tolerance must be positive");
  require(o.max_calibration_solves >= 1, "validate", "at least one calibration solve needed");
  validate(o.subdivision);
  validate(o.flatten);
}

GeometricLens::GeometricLens(double width, double height, const LensOptions& options)
    : width_(width), height_(height), options_(options) {
  validate(options);
  grid_ = make_grid(width, height, options.mesh);
}

// The area solved: the image, or a local patch around the lenses (kFocus: their footprints).
Eigen::AlignedBox2d GeometricLens::solved_box(const std::vector<Lens>& lenses) const {
  const Eigen::AlignedBox2d image(Eigen::Vector2d::Zero(), Eigen::Vector2d(width_, height_));
  const bool focus = model_for(lenses) == LensModel::kFocus;
  if ((options_.extent == Extent::kGlobal && !focus) || lenses.empty()) return image;
  Eigen::AlignedBox2d box;
  if (focus) {
    // Every footprint lies within its group's reach plus margin of the group's centre.
    for (const FocusGroup& g : focus_groups(lenses)) {
      const Eigen::Vector2d half = Eigen::Vector2d::Constant(g.reach + g.margin);
      box.extend(g.centre - half).extend(g.centre + half);
    }
    return box.intersection(image);
  }
  for (const Lens& lens : lenses) {
    const Eigen::Vector2d centre = lens.region.bounds().center();
    const Eigen::Vector2d half = 0.5 * lens.region.bounds().sizes().array() +
                                 (options_.extent_factor - 1) * lens.region.size();
    box.extend(centre - half).extend(centre + half);
  }
  return box.intersection(image);
}

// The grid the lift is built on: the image's, or one over the solved box whose border carries
// the sides flags so the flattening pins it; for focus lenses on circles, with vertices on every
// focus circle and footprint edge.
Grid GeometricLens::base_grid(const std::vector<Lens>& lenses, Eigen::AlignedBox2d& box) const {
  box = solved_box(lenses);
  const Eigen::AlignedBox2d image(Eigen::Vector2d::Zero(), Eigen::Vector2d(width_, height_));
  if (box.isApprox(image) && model_for(lenses) != LensModel::kFocus) return grid_;
  Grid patch = make_grid(box.sizes().x(), box.sizes().y(), options_.mesh);
  if (model_for(lenses) == LensModel::kFocus &&
      meshed_along_circles(lenses, cell_size(box, options_.mesh))) {
    // Vertices on every focus circle and footprint edge, so no triangle crosses them.
    std::vector<Ring> rings;
    for (const Lens& lens : lenses)
      rings.push_back({lens.region.peak() - box.min(), lens.region.size()});
    for (const FocusGroup& g : focus_groups(lenses))
      rings.push_back({g.centre - box.min(), g.reach + g.margin});
    static_cast<PlanarMesh&>(patch) =
        ringed_grid(box.sizes().x(), box.sizes().y(), options_.mesh, rings);
  }
  patch.V.rowwise() += box.min().transpose();
  return patch;
}

LensModel GeometricLens::model_for(const std::vector<Lens>& lenses) const {
  if (options_.model != LensModel::kAuto) return options_.model;
  for (const Lens& lens : lenses)
    if (lens.region.kind() != RegionKind::kCircle) return LensModel::kField;
  return LensModel::kLift;
}

std::vector<Lens> GeometricLens::fitted(const std::vector<Lens>& lenses, std::vector<double>& fits,
                                        Grid& grid, Eigen::AlignedBox2d& box) const {
  fits.clear();
  if (model_for(lenses) != LensModel::kFocus) {
    grid = base_grid(lenses, box);
    return lenses;
  }
  for (const Lens& lens : lenses) validate_lens(lens, width_, height_);
  box = solved_box(lenses);
  const double cell = cell_size(box, options_.mesh);
  fits = fitting_zooms(lenses, cell, focus_band(lenses, cell), width_, height_);
  std::vector<Lens> out = lenses;
  auto lower = [&](const std::vector<double>& caps) {
    for (size_t k = 0; k < out.size(); ++k) {
      fits[k] = std::min(fits[k], caps[k]);
      if (out[k].zoom <= fits[k]) continue;
      out[k].footprint = footprint_ratio(out[k]);  // the footprint asked for stays
      out[k].zoom = std::max(1.0, fits[k]);
    }
  };
  lower(fits);
  // Then what the mesh of the clamped lenses, the one they are solved on, holds without folding.
  grid = base_grid(out, box);
  const double out_cell = cell_size(box, options_.mesh);
  lower(unfolding_zooms(grid, out, out_cell, focus_band(out, out_cell), width_, height_));
  return out;
}

FlattenOptions GeometricLens::flatten_options(LensModel model) const {
  FlattenOptions o = options_.flatten;
  if (model == LensModel::kFocus) {
    // The footprints' box: its sides inside the image are pinned (focus_field), those on the
    // image border slide.
    o.boundary = Boundary::kSliding;
    o.standard = Standard::kScaled;
    o.weights = FlattenWeights::kCotan;
    return o;
  }
  if (options_.extent == Extent::kLocal) o.boundary = Boundary::kFixed;
  if (model == LensModel::kField) {
    // The rest areas already weigh the magnified triangles; the paper's (1 + h) A weights on
    // top made the focus so stiff that the context folded into a band one triangle wide.
    o.standard = Standard::kScaled;
    o.weights = FlattenWeights::kCotan;
  }
  return o;
}

// Lifts `mesh` (covering `box`) and maps the texture onto it, filling r's heights, mesh, box,
// source coordinates and the lift and texture timings (from `start`).
Lifted GeometricLens::lift_and_texture(const std::vector<Lens>& lenses,
                                       const std::vector<double>& heights, const PlanarMesh& mesh,
                                       const Eigen::AlignedBox2d& box, Clock::time_point start,
                                       LensResult& r, FocusField& focus) const {
  r.model = model_for(lenses);
  r.heights = heights;
  r.mesh = mesh;
  r.box = box;
  Lifted lifted;
  if (r.model == LensModel::kFocus) {
    // The focus field read as a lift (for --export-mesh): z = log zoom times the solved area's
    // long side.
    const double cell = cell_size(box, options_.mesh);
    focus = focus_field(r.mesh.V, lenses, heights, cell, focus_band(lenses, cell), width_, height_);
    lifted.V.resize(r.mesh.V.rows(), 3);
    lifted.V.leftCols<2>() = r.mesh.V;
    lifted.V.col(2) = focus.log_scale * box.sizes().maxCoeff();
    lifted.level = focus.level;
    lifted.log_zoom = focus.log_scale;
    lifted.inside.resize(size_t(r.mesh.V.rows()));
    for (size_t i = 0; i < lifted.inside.size(); ++i)
      lifted.inside[i] = focus.constraints.focus[i] >= 0;
  } else {
    lifted = lift(r.mesh.V, lenses, heights);
  }
  r.timings.lift = ms_since(start);
  const auto t = Clock::now();
  texture(lifted, r);
  r.timings.texture = ms_since(t);
  return lifted;
}

// Texture coordinates of the lifted mesh, with the fold fallback; the field model keeps them.
void GeometricLens::texture(const Lifted& lifted, LensResult& r) const {
  if (r.model == LensModel::kField || r.model == LensModel::kFocus) {
    r.warp.source = r.mesh.V;
    return;
  }
  std::vector<char> fixed(lifted.inside.size());
  for (size_t i = 0; i < fixed.size(); ++i) fixed[i] = !lifted.inside[i] || r.mesh.sides[i] != 0;
  r.warp.source = harmonic_texture(lifted.V, r.mesh.F, fixed, r.mesh.V, options_.texture);
  if (options_.texture == TextureWeights::kCotan && count_folds(r.warp.source, r.mesh.F) > 0) {
    // Negative cotan weights folded the map (steep walls): redo it with non-negative weights.
    r.warp.source =
        harmonic_texture(lifted.V, r.mesh.F, fixed, r.mesh.V, TextureWeights::kPositiveCotan);
    r.texture_fallback = true;
  }
}

// After the flattening: the framed WarpMesh and the zoom measured at each lens's peak.
void GeometricLens::finish(const std::vector<Lens>& lenses, const Lifted& lifted,
                           LensResult& r) const {
  r.lifted = lifted.V;
  r.flat = r.flattening.X;
  r.warp.F = r.mesh.F;
  r.warp.screen = frame(r.flat, flatten_options(r.model).boundary, width_, height_);
  r.warp.screen_width = int(std::lround(width_));
  r.warp.screen_height = int(std::lround(height_));
  const Eigen::AlignedBox2d image(Eigen::Vector2d::Zero(), Eigen::Vector2d(width_, height_));
  if (!r.box.isApprox(image)) add_identity_frame(r.warp, r.mesh, r.box, width_, height_);
  const double cell = cell_size(r.box, options_.mesh);
  for (const Lens& lens : lenses) {
    const double radius = std::max(cell, 0.05 * lens.region.size());
    r.zoom_measured.push_back(magnification_at(r.warp, lens.region.peak(), radius));
  }
  r.solves = 1;
}

LensResult GeometricLens::solve_with_heights(const std::vector<Lens>& lenses,
                                             const std::vector<double>& heights) const {
  Eigen::AlignedBox2d box;
  const Grid grid = base_grid(lenses, box);
  return solve_on(grid, box, lenses, heights);
}

LensResult GeometricLens::solve_on(const Grid& grid, const Eigen::AlignedBox2d& box,
                                   const std::vector<Lens>& lenses,
                                   const std::vector<double>& heights) const {
  const auto start = Clock::now();
  LensResult r;
  const PlanarMesh mesh =
      model_for(lenses) == LensModel::kFocus
          ? PlanarMesh(grid)
          : subdivide(
                grid, [&](const Eigen::Vector2d& p) { return lift_height(lenses, heights, p); },
                options_.subdivision);
  FocusField focus;
  const Lifted lifted = lift_and_texture(lenses, heights, mesh, box, start, r, focus);

  auto t = Clock::now();
  Flattener flattener(lifted.V, r.mesh.F, lifted.level, r.mesh.sides, flatten_options(r.model),
                      lifted.log_zoom, focus.constraints);
  r.timings.factorize = ms_since(t);

  t = Clock::now();
  if (r.model == LensModel::kFocus) {
    const double cell = cell_size(box, options_.mesh);
    r.flattening = flatten_focus(flattener, r.mesh.V, lenses, focus.groups, cell,
                                 focus_band(lenses, cell), width_, height_);
  } else {
    r.flattening = flattener.solve(r.mesh.V);
  }
  r.timings.iterate = ms_since(t);

  finish(lenses, lifted, r);
  r.timings.total = ms_since(start);
  return r;
}

// The interactive path: the base grid (no subdivision, so the topology and the symbolic
// factorization stay), the flattener refitted numerically, and the previous flattening as the
// starting point.
LensResult GeometricLens::solve_cached(const Grid& grid, const Eigen::AlignedBox2d& box,
                                       const std::vector<Lens>& lenses,
                                       const std::vector<double>& heights) {
  const auto start = Clock::now();
  LensResult r;
  FocusField focus;
  const Lifted lifted = lift_and_texture(lenses, heights, grid, box, start, r, focus);

  auto t = Clock::now();
  // A local patch has the same topology wherever it is, as long as its size is unchanged; a
  // focus lens's also needs the same pinned vertices.
  const bool same_topology = cache_.flattener && cache_.flat.rows() == r.mesh.V.rows() &&
                             (cache_.box.sizes() - r.box.sizes()).norm() < 1e-9 &&
                             focus.constraints.pinned == cache_.pinned &&
                             cache_.faces.rows() == r.mesh.F.rows() && cache_.faces == r.mesh.F;
  if (same_topology && cache_.model == r.model) {
    cache_.flattener->reweight(lifted.V, lifted.level, lifted.log_zoom, focus.constraints);
    const Eigen::RowVector2d shift = (r.box.min() - cache_.box.min()).transpose();
    cache_.flat.rowwise() += shift;
    if (cache_.predicted.rows() == cache_.flat.rows()) cache_.predicted.rowwise() += shift;
  } else {
    cache_.flattener =
        std::make_unique<Flattener>(lifted.V, r.mesh.F, lifted.level, r.mesh.sides,
                                    flatten_options(r.model), lifted.log_zoom, focus.constraints);
    cache_.flat = r.mesh.V;
    cache_.predicted.resize(0, 2);
  }
  cache_.box = r.box;
  cache_.pinned = std::move(focus.constraints.pinned);
  cache_.faces = r.mesh.F;
  cache_.model = r.model;
  r.timings.factorize = ms_since(t);

  t = Clock::now();
  // A lens dragged steadily moves its flattening steadily: the last update's change added again
  // is the better start (unless it folds a triangle; after a stop or a jump it costs at most an
  // iteration). A focus lens has a better one still: its power-law start.
  const bool predicted = cache_.predicted.rows() == cache_.flat.rows();
  if (r.model == LensModel::kFocus) {
    const double cell = cell_size(box, options_.mesh);
    r.flattening = flatten_focus(*cache_.flattener, r.mesh.V, lenses, focus.groups, cell,
                                 focus_band(lenses, cell), width_, height_);
  } else {
    r.flattening = cache_.flattener->solve(cache_.flat, predicted ? &cache_.predicted : nullptr);
  }
  cache_.predicted.resize(0, 2);  // only the first solve of an update has one
  cache_.flat = r.flattening.X;
  r.timings.iterate = ms_since(t);

  finish(lenses, lifted, r);
  r.timings.total = ms_since(start);
  return r;
}

LensResult GeometricLens::solve(const std::vector<Lens>& asked) const {
  std::vector<double> fits;
  Grid grid;
  Eigen::AlignedBox2d box;
  const std::vector<Lens> lenses = fitted(asked, fits, grid, box);
  std::vector<double> h;
  const LensModel model = model_for(lenses);
  for (const Lens& lens : lenses)
    h.push_back(lens.zoom == 1 ? 0.0 : initial_height(lens, model, grid.cell));
  LensResult r = calibrate(lenses, h, [&](const std::vector<double>& heights) {
    return solve_on(grid, box, lenses, heights);
  });
  r.zoom_fits = std::move(fits);
  return r;
}

const LensResult& GeometricLens::update(const std::vector<Lens>& asked) {
  std::vector<double> fits;
  Grid grid;
  Eigen::AlignedBox2d box;
  const std::vector<Lens> lenses = fitted(asked, fits, grid, box);
  // Start from the heights found last time for a lens of the same shape, size and zoom (and
  // model): after a move, one solve usually confirms them.
  const LensModel model = model_for(lenses);
  auto guess = [&](const Lens& lens) { return initial_height(lens, model, grid.cell); };
  std::vector<double> h;
  for (size_t k = 0; k < lenses.size(); ++k) {
    const Lens& lens = lenses[k];
    const bool known = k < cache_.lenses.size() && cache_.result.model == model &&
                       cache_.lenses[k].zoom == lens.zoom &&
                       cache_.lenses[k].profile == lens.profile &&
                       cache_.lenses[k].region.kind() == lens.region.kind() &&
                       cache_.lenses[k].region.size() == lens.region.size();
    h.push_back(lens.zoom == 1 ? 0.0 : known ? cache_.result.heights[k] : guess(lens));
  }
  Eigen::MatrixX2d before = cache_.flat;
  const Eigen::Vector2d box_before = cache_.box.min();
  if (cache_.change.rows() == before.rows()) cache_.predicted = before + cache_.change;
  cache_.result = calibrate(lenses, h, [&](const std::vector<double>& heights) {
    return solve_cached(grid, box, lenses, heights);
  });
  cache_.result.zoom_fits = std::move(fits);
  cache_.lenses = lenses;
  cache_.change.resize(0, 2);
  if (before.rows() == cache_.flat.rows()) {
    // In the current patch's coordinates (a local patch moves with its lens).
    before.rowwise() += (cache_.box.min() - box_before).transpose();
    cache_.change = cache_.flat - before;
  }
  return cache_.result;
}

LensResult GeometricLens::calibrate(
    const std::vector<Lens>& lenses, std::vector<double> h,
    const std::function<LensResult(const std::vector<double>&)>& run) const {
  for (const Lens& lens : lenses) validate_lens(lens, width_, height_);
  const size_t n = lenses.size();
  // Per lens, a bracket [lo, hi] of heights on f(h) = log(zoom(h)) - log(target), f(0) < 0,
  // refined by false position (Illinois variant: an end kept twice has its f halved).
  std::vector<double> lo(n, 0), hi(n, -1), f_lo(n), f_hi(n, 0);
  std::vector<int> last_side(n, 0);
  for (size_t k = 0; k < n; ++k) f_lo[k] = -std::log(lenses[k].zoom);
  const LensModel model = model_for(lenses);
  // The largest height tried: a focus's log zoom, the field's peak log zoom, or the lift's
  // height over the region's size.
  auto cap = [&](const Lens& lens) {
    if (model == LensModel::kFocus) return kMaxFieldLogZoom;
    return lens.region.size() *
           (model == LensModel::kField ? kMaxFieldLogZoom : kMaxHeightOverSize);
  };
  StageTimings sum;
  LensResult best;
  double best_miss = std::numeric_limits<double>::infinity();
  for (int solve = 1;; ++solve) {
    LensResult r = run(h);
    sum.lift += r.timings.lift;
    sum.texture += r.timings.texture;
    sum.factorize += r.timings.factorize;
    sum.iterate += r.timings.iterate;
    sum.total += r.timings.total;
    // Keep the solve whose worst lens is closest to its zoom, should calibration not converge.
    double miss = 0;
    for (size_t k = 0; k < n; ++k)
      miss = std::max(miss, std::abs(std::log(r.zoom_measured[k] / lenses[k].zoom)));
    bool done = true;
    for (size_t k = 0; k < n; ++k) {
      if (h[k] == 0) continue;
      const double gain = std::log(r.zoom_measured[k]);
      const double f = gain - std::log(lenses[k].zoom);
      if (std::abs(f) <= std::log1p(options_.zoom_tolerance)) continue;
      done = false;
      const int side = f < 0 ? -1 : 1;
      if (side < 0) {
        lo[k] = h[k];
        f_lo[k] = f;
        if (last_side[k] < 0) f_hi[k] *= 0.5;
      } else {
        hi[k] = h[k];
        f_hi[k] = f;
        if (last_side[k] > 0) f_lo[k] *= 0.5;
      }
      last_side[k] = side;
      if (hi[k] < 0) {
        // No upper end yet: scale the height by the first guess's ratio between the zoom
        // wanted and the zoom reached (the guess's curve through h = 0), at most doubling.
        h[k] = gain > 0
                   ? std::min(2.0 * h[k], h[k] * height_for_zoom(lenses[k], model, lenses[k].zoom) /
                                              height_for_zoom(lenses[k], model, std::exp(gain)))
                   : 2.0 * h[k];
      } else {
        h[k] = lo[k] + (hi[k] - lo[k]) * f_lo[k] / (f_lo[k] - f_hi[k]);
      }
      // Taller bumps only fold: a lens that has not reached its zoom at 20 sizes never will.
      h[k] = std::min(h[k], cap(lenses[k]));
    }
    if (miss < best_miss) {
      best_miss = miss;
      best = std::move(r);
    }
    // A focus lens's zoom is its focus's scale, not a result to aim for: one solve.
    if (done || solve >= options_.max_calibration_solves || model == LensModel::kFocus) {
      best.solves = solve;
      break;
    }
  }
  best.timings = sum;
  return best;
}

}  // namespace geolens
