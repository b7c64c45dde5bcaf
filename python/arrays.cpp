#include "arrays.h"

#include <cstring>
#include <string>

#include "geolens/core/errors.h"

namespace geolens::python {

namespace {

std::string describe(const py::array& array) {
  std::string shape = "(";
  for (py::ssize_t k = 0; k < array.ndim(); ++k)
    shape += (k ? ", " : "") + std::to_string(array.shape(k));
  if (array.ndim() == 1) shape += ",";
  return std::string(py::str(array.dtype())) + " array of shape " + shape + ")";
}

// `array` as a C-contiguous array of T: itself if it is one, else a copy.
template <typename T>
py::array_t<T, py::array::c_style> contiguous(const py::array& array) {
  return py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(array);
}

}  // namespace

Image to_image(const py::array& array, const char* function) {
  const bool uint8 = array.dtype().kind() == 'u' && array.dtype().itemsize() == 1;
  const bool shaped =
      array.ndim() == 2 || (array.ndim() == 3 && array.shape(2) >= 1 && array.shape(2) <= 4);
  require(uint8 && shaped && array.shape(0) > 0 && array.shape(1) > 0, function,
          "image must be an H x W or H x W x C (C in 1..4) uint8 array, got a " + describe(array));
  const auto pixels = contiguous<uint8_t>(array);
  Image image(int(array.shape(1)), int(array.shape(0)),
              array.ndim() == 3 ? int(array.shape(2)) : 1);
  std::memcpy(image.pixels.data(), pixels.data(), image.pixels.size());
  return image;
}

Image to_mask(const py::array& array, const char* function) {
  const char kind = array.dtype().kind();
  require((kind == 'b' || kind == 'u' || kind == 'i') && array.ndim() == 2 && array.shape(0) > 0 &&
              array.shape(1) > 0,
          function, "mask must be an H x W array of bool or integers, got a " + describe(array));
  const auto inside = contiguous<bool>(py::array(array.attr("astype")("bool")));
  Image mask(int(array.shape(1)), int(array.shape(0)), 1);
  for (size_t k = 0; k < mask.pixels.size(); ++k) mask.pixels[k] = inside.data()[k] ? 255 : 0;
  return mask;
}

py::array to_array(Image image, bool grey_2d) {
  auto* owned = new Image(std::move(image));
  const py::capsule free_image(owned, [](void* p) { delete static_cast<Image*>(p); });
  const py::ssize_t h = owned->height, w = owned->width, c = owned->channels;
  if (grey_2d && c == 1) return py::array_t<uint8_t>({h, w}, owned->pixels.data(), free_image);
  return py::array_t<uint8_t>({h, w, c}, owned->pixels.data(), free_image);
}

Eigen::MatrixX2d to_points(const py::array& array, const char* function) {
  const char kind = array.dtype().kind();
  require((kind == 'f' || kind == 'i' || kind == 'u') && array.ndim() == 2 && array.shape(1) == 2,
          function, "points must be an N x 2 array of numbers, got a " + describe(array));
  const auto values = contiguous<double>(array);
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>>(
      values.data(), array.shape(0), 2);
}

}  // namespace geolens::python
