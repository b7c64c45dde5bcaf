#pragma once
// The keyword arguments of magnify(), GeometricLens() and compare() (the CLI's lens options), and
// the lens lists every call takes.

#include <pybind11/pybind11.h>

#include <vector>

#include "geolens/lens/geometric_lens.h"

namespace geolens::python {

namespace py = pybind11;

/// The solver options named in `kwargs` (lens_option_fields, lens/lens_options.h: the CLI's
/// options, '-' written '_', and draft_mesh), the others at LensOptions's defaults. Throws
/// TypeError naming `function` for an unknown name or a value of the wrong type, InvalidInput for a
/// value out of range (validate).
LensOptions lens_options(const py::kwargs& kwargs, const char* function);

/// The docstring lines that list lens_options's keywords and their defaults.
std::string lens_options_doc();

/// A Lens, or a sequence of Lens and of sequences of Lens (what mask() returns), as one list.
/// Throws InvalidInput naming `function` for anything else or an empty list.
std::vector<Lens> to_lenses(const py::handle& lenses, const char* function);

}  // namespace geolens::python
