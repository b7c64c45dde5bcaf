#pragma once
// numpy arrays in and out of the library's types: images, masks, point lists.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>

#include "geolens/io/image.h"

namespace geolens::python {

namespace py = pybind11;

/// An H x W (grey) or H x W x C (C in [1, 4]) uint8 array, any strides, as an Image (a copy:
/// an Image owns its pixels). Throws InvalidInput naming `function` for another dtype or shape.
Image to_image(const py::array& array, const char* function);

/// An H x W array of bool or integers as a one-channel mask: 255 where non-zero, 0 elsewhere.
/// Throws InvalidInput naming `function` for another dtype or shape.
Image to_mask(const py::array& array, const char* function);

/// `image` as an H x W x C uint8 array that owns its pixels (moved, not copied); H x W when
/// `grey_2d` and the image has one channel.
py::array to_array(Image image, bool grey_2d = false);

/// An N x 2 array of numbers (any numeric dtype, any strides) as float64 points. Throws
/// InvalidInput naming `function` for another dtype or shape.
Eigen::MatrixX2d to_points(const py::array& array, const char* function);

}  // namespace geolens::python
