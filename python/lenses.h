#pragma once
// geolens.Lens and the calls that make lenses: circle(), polygon(), mask().

#include <pybind11/pybind11.h>

namespace geolens::python {

/// Registers Lens, circle, polygon and mask on `module`.
void bind_lenses(pybind11::module_& module);

}  // namespace geolens::python
