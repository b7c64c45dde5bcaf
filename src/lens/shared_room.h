#pragma once
// Private: the zooms of focus lenses that are near each other, before GeometricLens's fit
// (docs/design.md, "Several lenses share room").

#include <functional>
#include <string>
#include <vector>

#include "geolens/lens/lens.h"
#include "lens/focus_lens.h"

namespace geolens {

/// The largest log zoom below `below` among fixed points of [0, ln kMaxZoom] (2^-20 of it apart)
/// at which `fits` holds, 0 if none: the same points whatever `below` is, so asking for more
/// never gets less by rounding. `fits` is taken to hold on one interval (it may fail near 0) and
/// not beyond it; the interval is found among 16 points, then by halvings.
double largest_fitting_log_zoom(double below, const std::function<bool(double)>& fits);

/// The mesh a set of lenses would be fitted on where they are the only ones (GeometricLens: the
/// cell of their solved box and the focus band on it).
using FitMeshOf = std::function<FitMesh(const std::vector<Lens>&)>;

/// `lenses` (focus model, on a width x height image) with the zooms that lenses near each other
/// get, the rest as asked; each set of lenses is fitted on `mesh_of` it (fitting_zooms):
///
/// - Apart, lens i gets min(c_i, L_i): c_i the log zoom it fits alone where it is (at most the
///   one asked), L_i the least over its neighbours j of the level L at which the two rings fit
///   side by side, each at the least of L and its own c: (r_i + band) e^(min(c_i, L) / 0.8) +
///   (r_j + band) e^(min(c_j, L) / 0.8) = |p_i - p_j| (reach r, peak p; ring_need). The
///   shortfall is shared by raising both to one level (the lens asked less keeps its zoom, the
///   other takes the room left), so two lenses that could both get 2 do, and every zoom is a
///   continuous function of the lenses' places, sizes and zooms, rising with the zoom asked.
/// - Lenses are magnified together (one focus group) only where that gives both at least as
///   much as apart: the pair in most conflict first, where the merged group's own fit is at
///   least both apart zooms and some two of their rings meet at it (so focus_groups groups them).
///   A merged group's lenses all get its zoom. Regions that overlap are always merged (apart they
///   get nothing).
///
/// Without `merge`, every lens stays apart. With `neighbours`, per lens the index of the lens
/// whose room set its zoom (the pair at the least level, where that is below its cap), else -1.
/// GeometricLens then lowers whatever still does not fit (an image side with a neighbour, the
/// mesh).
std::vector<Lens> shared_room_zooms(const std::vector<Lens>& lenses, const FitMeshOf& mesh_of,
                                    double width, double height, bool merge = true,
                                    std::vector<int>* neighbours = nullptr);

/// Why a lens gets less than asked where lens `neighbour` (an index) took the room: "lens N
/// beside it (...)", with a remedy.
std::string beside_reason(size_t neighbour);

}  // namespace geolens
