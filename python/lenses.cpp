#include "lenses.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <sstream>
#include <string>
#include <vector>

#include "arrays.h"
#include "geolens/geometry/roi.h"
#include "geolens/lens/lens.h"

namespace geolens::python {

namespace py = pybind11;

namespace {

// A lens on `region` with the keywords every lens takes, the zoom checked now (the rest, which
// depends on the image, when it is solved: validate_lens).
Lens make_lens(Region region, double zoom, const std::string& profile, double footprint,
               const char* function) {
  require_zoom(zoom, function);
  return Lens{std::move(region), zoom, parse_profile(profile), footprint};
}

std::string repr(const Lens& lens) {
  std::ostringstream out;
  out << "geolens." << lens.region.kind() << "(";
  if (const auto circle = lens.region.circle())
    out << circle->center.x() << ", " << circle->center.y() << ", " << circle->radius << ", ";
  else
    out << "peak=(" << lens.region.peak().x() << ", " << lens.region.peak().y() << "), ";
  out << "zoom=" << lens.zoom << ", profile='" << to_string(lens.profile)
      << "', footprint=" << lens.footprint << ")";
  return out.str();
}

}  // namespace

void bind_lenses(py::module_& m) {
  const Lens defaults{Region::circle(Eigen::Vector2d::Zero(), 1)};
  const std::string lens_keywords =
      "zoom: the magnification, in [1, 8]; profile: the bump of the lift and field models, "
      "'gaussian', 'sphere' or 'mesa'; footprint: focus model, how far the context gives way, "
      "as a ratio of the region's reach, above the zoom (0: 2 x zoom). Coordinates are source "
      "pixels, origin top-left, y down.";

  py::class_<Lens>(m, "Lens",
                   "A lens: its region, zoom, profile and footprint. Made by circle(), polygon() "
                   "and mask(); read-only.")
      .def_property_readonly(
          "kind", [](const Lens& l) { return l.region.kind(); }, "'circle', 'polygon' or 'mask'")
      .def_readonly("zoom", &Lens::zoom)
      .def_property_readonly("profile", [](const Lens& l) { return to_string(l.profile); })
      .def_readonly("footprint", &Lens::footprint)
      .def_property_readonly(
          "bounds",
          [](const Lens& l) {
            const Eigen::AlignedBox2d box = l.region.bounds();
            return py::make_tuple(box.min().x(), box.min().y(), box.max().x(), box.max().y());
          },
          "(x0, y0, x1, y1), pixels")
      .def_property_readonly(
          "peak",
          [](const Lens& l) { return py::make_tuple(l.region.peak().x(), l.region.peak().y()); },
          "(x, y) where the region is thickest and the zoom is measured, pixels")
      .def_property_readonly(
          "size", [](const Lens& l) { return l.region.size(); },
          "the region's largest half-width (a circle's radius), pixels")
      .def("__repr__", &repr);

  m.def(
      "circle",
      [](double cx, double cy, double r, double zoom, const std::string& profile,
         double footprint) {
        return make_lens(Region::circle({cx, cy}, r), zoom, profile, footprint, "circle");
      },
      py::arg("cx"), py::arg("cy"), py::arg("r"), py::kw_only(), py::arg("zoom") = defaults.zoom,
      py::arg("profile") = to_string(defaults.profile), py::arg("footprint") = defaults.footprint,
      ("A circle lens of centre (cx, cy) and radius r. " + lens_keywords).c_str());

  m.def(
      "polygon",
      [](const py::array& points, double zoom, const std::string& profile, double footprint) {
        const Eigen::MatrixX2d p = to_points(points, "polygon");
        std::vector<Eigen::Vector2d> vertices;
        for (Eigen::Index k = 0; k < p.rows(); ++k) vertices.emplace_back(p.row(k));
        return make_lens(Region::polygon(vertices), zoom, profile, footprint, "polygon");
      },
      py::arg("points"), py::kw_only(), py::arg("zoom") = defaults.zoom,
      py::arg("profile") = to_string(defaults.profile), py::arg("footprint") = defaults.footprint,
      ("A polygon lens: points, an N x 2 array of its vertices (a simple polygon, either "
       "orientation, not closed explicitly). " +
       lens_keywords)
          .c_str());

  m.def(
      "mask",
      [](const py::array& mask, double zoom, const std::string& profile, double footprint) {
        const Image image = to_mask(mask, "mask");
        std::vector<Lens> lenses;
        for (Region& region : Region::from_mask(image))
          lenses.push_back(make_lens(std::move(region), zoom, profile, footprint, "mask"));
        return lenses;
      },
      py::arg("mask"), py::kw_only(), py::arg("zoom") = defaults.zoom,
      py::arg("profile") = to_string(defaults.profile), py::arg("footprint") = defaults.footprint,
      ("The lenses of a mask: an H x W array of bool or integers of the source's size, non-zero "
       "inside. Returns a list with one lens per 8-connected blob, in raster order of their "
       "first pixel (as the CLI's mask:FILE); pass it as it is, or in a list with other lenses. " +
       lens_keywords)
          .c_str());
}

}  // namespace geolens::python
