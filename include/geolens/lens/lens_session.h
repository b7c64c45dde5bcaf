#pragma once
// The interactive face of the geometric lens: one object a GUI loop (or its worker thread) calls
// every frame.

#include <memory>
#include <vector>

#include "geolens/core/solve_control.h"
#include "geolens/lens/geometric_lens.h"

namespace geolens {

/// A GeometricLens that remembers what one frame leaves for the next. update() reuses what did
/// not change since the last call: the flattener and its symbolic factorization while the mesh's
/// topology stays (a local patch of the same size, the same pinned vertices), the previous
/// flattening (or, for a lens dragged steadily, the last change added again) as the start, the
/// calibrated heights of a lens of the same shape, size and zoom; a focus lens starts from its
/// power-law start. The mesh is the base grid (no subdivision, so the topology stays).
///
/// Results belong to the caller: a UI thread may draw the last one while update() computes the
/// next on a worker thread (see LensWorker). One session is used by one thread at a time.
class LensSession {
 public:
  /// A session on a width x height image (pixels) with `options`, as GeometricLens checks them.
  LensSession(double width, double height, const LensOptions& options = {});
  ~LensSession();
  LensSession(LensSession&&) noexcept;             ///< moves the lens and what it remembers
  LensSession& operator=(LensSession&&) noexcept;  ///< moves the lens and what it remembers

  /// The lenses of this frame, solved as GeometricLens::solve() would (zoom calibrated and
  /// checked the same way). Throws InvalidInput for an invalid lens (the session is unchanged),
  /// SolverError if a system cannot be solved, Cancelled if `control` stops it (the next update
  /// starts from the last finished frame).
  ///
  /// A draft is solved on the grid of LensOptions::draft_mesh, and (focus model) on a mesh that
  /// follows the regions and footprints but is not refined where the ring bends
  /// (LensOptions::mesh_tolerance): a drag's frames, about as fast as the grid alone; its
  /// result says `draft` where it differs from a full frame. Where a draft grid cannot hold a
  /// lens's zoom (GeometricLens's mesh_limited), the draft is solved on a grid twice as fine, and
  /// so on while that is coarser than LensOptions::mesh, then in full. Drafts and full frames (and
  /// each draft grid) keep what they leave for the next apart, so a full frame between two drafts
  /// costs neither its speed.
  LensResult update(const std::vector<Lens>& lenses, const SolveControl& control = {},
                    bool draft = false);

  /// Forgets every frame: the next update() starts as a first placement.
  void reset();

  const GeometricLens& lens() const { return lens_; }  ///< the lens it solves with

 private:
  struct State;
  // Level 0 a full frame, level k >= 1 a draft on drafts_[k - 1] (on lens_ without draft grids).
  LensResult solve(const std::vector<Lens>& lenses, const SolveControl& control, size_t level);

  GeometricLens lens_;
  std::vector<GeometricLens> drafts_;  // draft grids, coarsest first (draft_options)
  std::unique_ptr<State> state_;
};

}  // namespace geolens
