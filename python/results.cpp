#include "results.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <chrono>
#include <mutex>

#include "arrays.h"
#include "geolens/eval/run_stats.h"
#include "geolens/lens/lens_session.h"
#include "geolens/measure/distortion.h"
#include "options.h"

namespace geolens::python {

namespace {

py::array_t<double> to_numpy(const std::vector<double>& values) {
  return py::array_t<double>(py::ssize_t(values.size()), values.data());
}

// geolens.GeometricLens: solve() on a GeometricLens (thread-safe, the GIL released), update() on
// the LensSession made on its first call (one update at a time, whatever the Python threads).
class GeometricLensObject {
 public:
  GeometricLensObject(double width, double height, const LensOptions& options)
      : lens_(width, height, options) {}

  LensSolveResult solve(const std::vector<Lens>& lenses) const {
    py::gil_scoped_release release;
    return LensSolveResult(lens_.solve(lenses), lenses, lens_.options());
  }

  LensSolveResult update(const std::vector<Lens>& lenses, bool draft) {
    py::gil_scoped_release release;
    const std::lock_guard lock(session_mutex_);
    if (!session_)
      session_ = std::make_unique<LensSession>(lens_.width(), lens_.height(), lens_.options());
    return LensSolveResult(session_->update(lenses, {}, draft), lenses, lens_.options());
  }

  void reset() {
    py::gil_scoped_release release;
    const std::lock_guard lock(session_mutex_);
    if (session_) session_->reset();
  }

  const GeometricLens& lens() const { return lens_; }

 private:
  GeometricLens lens_;
  std::mutex session_mutex_;
  std::unique_ptr<LensSession> session_;
};

}  // namespace

py::object parse_json(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

MagnificationResult::MagnificationResult(Magnification m)
    : warp(std::make_shared<WarpMap>(std::move(m.warp))),
      zoom_parameter(std::move(m.zoom_parameter)),
      zoom_measured(std::move(m.zoom_measured)),
      draft(m.draft) {}

LensSolveResult::LensSolveResult(LensResult solved, std::vector<Lens> lenses_solved,
                                 const LensOptions& solved_with)
    : MagnificationResult(solved),
      result(std::move(solved)),
      lenses(std::move(lenses_solved)),
      options(solved_with) {}

const std::string& LensSolveResult::stats_json() const {
  if (!stats_) {
    const auto start = std::chrono::steady_clock::now();
    const DistortionSummary distortion = summarize(measure_triangles(result.warp));
    RunTimings timings;
    timings.measure =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stats_ = run_stats_json(lenses, options, result, distortion, timings);
  }
  return *stats_;
}

namespace {

// Warp: the mesh as read-only numpy views, forward and inverse.
void bind_warp(py::module_& m) {
  py::class_<WarpMap, std::shared_ptr<WarpMap>>(
      m, "Warp",
      "A lens's warp: a triangle mesh with, per vertex, its position in the source image and on "
      "the screen (pixels, origin top-left, y down), and the map between them.")
      .def_property_readonly(
          "F", [](const WarpMap& w) -> const Eigen::MatrixX3i& { return w.mesh().F; },
          "#F x 3 int32 vertex indices (read-only view), counter-clockwise in source "
          "coordinates (y down)")
      .def_property_readonly(
          "source", [](const WarpMap& w) -> const Eigen::MatrixX2d& { return w.mesh().source; },
          "#V x 2 float64 source positions, pixels (read-only view)")
      .def_property_readonly(
          "screen", [](const WarpMap& w) -> const Eigen::MatrixX2d& { return w.mesh().screen; },
          "#V x 2 float64 screen positions, pixels (read-only view)")
      .def_property_readonly(
          "screen_size",
          [](const WarpMap& w) {
            return py::make_tuple(w.mesh().screen_width, w.mesh().screen_height);
          },
          "(width, height) the screen positions are framed for, pixels")
      .def(
          "forward",
          [](const WarpMap& w, const py::array& points) {
            const Eigen::MatrixX2d p = to_points(points, "Warp.forward");
            py::gil_scoped_release release;
            return w.forward_batch(p);
          },
          py::arg("points"),
          "Where source points land on the screen: N x 2 source pixels in, N x 2 float64 screen "
          "pixels out, a row of NaN where a point is in no triangle (outside the image).")
      .def(
          "inverse",
          [](const WarpMap& w, const py::array& points) {
            const Eigen::MatrixX2d p = to_points(points, "Warp.inverse");
            py::gil_scoped_release release;
            return w.inverse_batch(p);
          },
          py::arg("points"),
          "The source points shown at screen points: N x 2 screen pixels in, N x 2 float64 "
          "source pixels out, a row of NaN where a point is in no triangle.")
      .def("__repr__", [](const WarpMap& w) {
        return "<geolens.Warp: " + std::to_string(w.mesh().F.rows()) + " triangles, " +
               std::to_string(w.mesh().source.rows()) + " vertices, screen " +
               std::to_string(w.mesh().screen_width) + " x " +
               std::to_string(w.mesh().screen_height) + ">";
      });
}

// Magnification, and LensResult: how the geometric lens solved.
void bind_magnifications(py::module_& m) {
  py::class_<MagnificationResult>(m, "Magnification",
                                  "What a lens built: its warp and, per lens, its zoom.")
      .def_readonly("warp", &MagnificationResult::warp)
      .def_property_readonly(
          "zoom_parameter", [](const MagnificationResult& r) { return to_numpy(r.zoom_parameter); },
          "per lens: the zoom it was built with (the geometric lens's after fitting, a classic "
          "lens's matched parameter)")
      .def_property_readonly(
          "zoom_measured", [](const MagnificationResult& r) { return to_numpy(r.zoom_measured); },
          "per lens: the magnification measured at its region's peak")
      .def_readonly("draft", &MagnificationResult::draft,
                    "solved on an unrefined mesh (GeometricLens.update(draft=True))");

  py::class_<LensSolveResult, MagnificationResult>(
      m, "LensResult", "The geometric lens's result: a Magnification, and how it was solved.")
      .def_property_readonly("model",
                             [](const LensSolveResult& r) { return to_string(r.result.model); })
      .def_property_readonly(
          "zoom_fits", [](const LensSolveResult& r) { return to_numpy(r.result.zoom_fits); },
          "focus model, per lens: the zoom it was solved at, the one asked where that fits, else "
          "the largest that does (empty otherwise)")
      .def_property_readonly(
          "zoom_fit_reasons", [](const LensSolveResult& r) { return r.result.zoom_fit_reasons; },
          "focus model, per lens: what limits its zoom where it gets at least 0.1 % less than "
          "asked, else '' (empty otherwise)")
      .def_property_readonly(
          "iterations", [](const LensSolveResult& r) { return r.result.flattening.iterations; })
      .def_property_readonly("converged",
                             [](const LensSolveResult& r) { return r.result.flattening.converged; })
      .def_property_readonly(
          "stats", [](const LensSolveResult& r) { return parse_json(r.stats_json()); },
          "the stats as a dict, the keys of the CLI's --stats (its timings: the solve's and "
          "the stats' own measures); measured on first use");
}

// GeometricLens: solve, and update frame after frame.
void bind_geometric_lens(py::module_& m) {
  py::class_<GeometricLensObject>(
      m, "GeometricLens",
      ("GeometricLens(width, height, **options): the geometric lens on a width x height source.\n"
       "options (the CLI's, '-' written '_'), with their defaults:\n" +
       lens_options_doc())
          .c_str())
      .def(py::init([](double width, double height, const py::kwargs& kwargs) {
             return std::make_unique<GeometricLensObject>(width, height,
                                                          lens_options(kwargs, "GeometricLens"));
           }),
           py::arg("width"), py::arg("height"))
      .def(
          "solve",
          [](const GeometricLensObject& lens, const py::object& lenses) {
            return lens.solve(to_lenses(lenses, "GeometricLens.solve"));
          },
          py::arg("lenses"),
          "Magnifies the lenses (a Lens or a list), independently of any earlier call; "
          "thread-safe, runs without the GIL. Returns a LensResult.")
      .def(
          "update",
          [](GeometricLensObject& lens, const py::object& lenses, bool draft) {
            return lens.update(to_lenses(lenses, "GeometricLens.update"), draft);
          },
          py::arg("lenses"), py::arg("draft") = false,
          "The lenses of the next frame, solved reusing what the last update left (a "
          "LensSession): faster when lenses move a little. draft: an unrefined mesh, faster "
          "still. Returns a LensResult.")
      .def("reset", &GeometricLensObject::reset,
           "Forgets every update: the next starts as a first placement.")
      .def_property_readonly("width", [](const GeometricLensObject& l) { return l.lens().width(); })
      .def_property_readonly("height",
                             [](const GeometricLensObject& l) { return l.lens().height(); });
}

}  // namespace

void bind_results(py::module_& m) {
  bind_warp(m);
  bind_magnifications(m);
  bind_geometric_lens(m);
}

}  // namespace geolens::python
