// The geolens Python module: numpy arrays in and out of the library (issue 17). Bindings only:
// every computation is the library's. Errors: geolens::InvalidInput (a std::invalid_argument)
// reaches Python as ValueError with its message, the library's other errors (std::runtime_error)
// as RuntimeError, as pybind11 translates them.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "arrays.h"
#include "geolens/core/errors.h"
#include "geolens/eval/comparison.h"
#include "geolens/io/image.h"
#include "geolens/lens/lens_method.h"
#include "geolens/lens/lens_options.h"
#include "geolens/render/render.h"
#include "lenses.h"
#include "options.h"
#include "results.h"

namespace py = pybind11;
using namespace geolens;
using namespace geolens::python;

namespace {

// `size`, None or (width, height), as the output's width and height; None: `fallback`.
std::pair<int, int> output_size(const py::object& size, std::pair<int, int> fallback,
                                const char* function) {
  if (size.is_none()) return fallback;
  try {
    return size.cast<std::pair<int, int>>();
  } catch (const py::cast_error&) {
    throw InvalidInput(std::string(function) + ": size must be None or (width, height), got " +
                       std::string(py::repr(size)));
  }
}

// `image` rendered through `warp` at `size` on `threads` threads (the caller releases the GIL).
Image render_image(const WarpMesh& warp, const Image& image, std::pair<int, int> size,
                   int threads) {
  RenderOptions options;
  options.width = size.first;
  options.height = size.second;
  options.threads = threads;
  return render(warp, MipPyramid(image), options);
}

// Python's magnify(): the image magnified by the lenses with the geometric lens, the CLI's
// warnings as UserWarnings.
py::array magnify_image(const py::array& image, const py::object& lenses, const py::object& size,
                        const py::kwargs& kwargs) {
  const Image source = to_image(image, "magnify");
  const std::vector<Lens> list = to_lenses(lenses, "magnify");
  const LensOptions options = lens_options(kwargs, "magnify");
  const std::pair<int, int> output = output_size(size, {source.width, source.height}, "magnify");
  Image magnified;
  std::vector<std::string> warnings;
  for (const UnreadOption& o : unread_options(options, list))
    warnings.push_back(o.name + " is ignored: " + o.reason);
  {
    py::gil_scoped_release release;
    const LensResult result = GeometricLens(source.width, source.height, options).solve(list);
    for (std::string& w : zoom_warnings(list, result)) warnings.push_back(std::move(w));
    magnified = render_image(result.warp, source, output, options.flatten.threads);
  }
  // As the CLI says them on stderr: an option the model does not read, a lens that did not
  // get the zoom asked.
  for (const std::string& w : warnings)
    if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1) < 0) throw py::error_already_set();
  return to_array(std::move(magnified), image.ndim() == 2);
}

// magnify, classic_lens and compare: lenses in, a picture, a Magnification or a report out.
void bind_lens_calls(py::module_& m) {
  m.def("magnify", &magnify_image, py::arg("image"), py::arg("lenses"),
        py::arg("size") = py::none(),
        ("magnify(image, lenses, size=None, **options) -> ndarray\n\n"
         "The image (H x W x C or H x W uint8) magnified by the lenses (a Lens or a list) with "
         "the geometric lens, rendered at size (width, height; None: the image's); the same "
         "dtype and channels out. options (the CLI's, '-' written '_'), with their defaults:\n" +
         lens_options_doc())
            .c_str());

  m.def(
      "classic_lens",
      [](const std::string& name, const py::object& lenses, int width, int height, int mesh) {
        const ClassicLens kind = parse_classic_lens(name);
        const std::vector<Lens> list = to_lenses(lenses, "classic_lens");
        ClassicOptions options;
        options.mesh = mesh;
        py::gil_scoped_release release;
        return MagnificationResult(ClassicMethod(kind, options).magnify(list, width, height));
      },
      py::arg("name"), py::arg("lenses"), py::arg("width"), py::arg("height"), py::kw_only(),
      py::arg("mesh") = ClassicOptions{}.mesh,
      "The classic lens `name` (one of CLASSIC_LENSES) on a width x height source, each circle "
      "lens read as the focus model does (its circle the focus, shown at its zoom, within its "
      "footprint), its zoom matched to the lens's; mesh: grid vertices along the long side. "
      "Returns a Magnification.");

  m.def(
      "compare",
      [](int width, int height, const py::object& lenses, std::optional<int> baseline_mesh,
         const py::kwargs& kwargs) {
        const std::vector<Lens> list = to_lenses(lenses, "compare");
        const LensOptions options = lens_options(kwargs, "compare");
        std::string report;
        {
          py::gil_scoped_release release;
          report = comparison_json(
              baseline_mesh ? compare_lenses(width, height, list, options, *baseline_mesh)
                            : compare_lenses(width, height, list, options));
        }
        return parse_json(report);
      },
      py::arg("width"), py::arg("height"), py::arg("lenses"), py::kw_only(),
      py::arg("baseline_mesh") = py::none(),
      ("compare(width, height, lenses, baseline_mesh=None, **options) -> dict\n\n"
       "The geometric lens measured against every classic lens matched to its zoom (circle "
       "lenses), as the report `geolens compare` writes (its JSON as a dict); baseline_mesh: the "
       "classic lenses' grid vertices along the long side (None: the CLI's default). options, "
       "as magnify's:\n" +
       lens_options_doc())
          .c_str());
}

// render, load_image and save_image: pictures through a warp, and image files.
void bind_image_calls(py::module_& m) {
  m.def(
      "render",
      [](const WarpMap& warp, const py::array& image, const py::object& size, int threads) {
        const Image source = to_image(image, "render");
        const WarpMesh& mesh = warp.mesh();
        const std::pair<int, int> output =
            output_size(size, {mesh.screen_width, mesh.screen_height}, "render");
        Image rendered;
        {
          py::gil_scoped_release release;
          rendered = render_image(mesh, source, output, threads);
        }
        return to_array(std::move(rendered), image.ndim() == 2);
      },
      py::arg("warp"), py::arg("image"), py::arg("size") = py::none(), py::kw_only(),
      py::arg("threads") = RenderOptions{}.threads,
      "The image (the warp's source, H x W x C or H x W uint8) drawn through a Warp at size "
      "(width, height; None: the warp's screen size), on threads threads (0: all cores).");

  m.def(
      "load_image",
      [](const std::string& path, long long max_pixels) {
        require(max_pixels >= 1, "load_image",
                "max_pixels must be >= 1, got " + std::to_string(max_pixels));
        Image image;
        {
          py::gil_scoped_release release;
          image = load_image(path, uint64_t(max_pixels));
        }
        return to_array(std::move(image));
      },
      py::arg("path"), py::arg("max_pixels") = kMaxImagePixels,
      "A PNG or JPEG file as an H x W x C uint8 array (C: 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA); "
      "a file of more than max_pixels pixels (2^28 unless raised) is refused from its header.");

  m.def(
      "save_image",
      [](const std::string& path, const py::array& image, std::optional<int> jpeg_quality) {
        const Image pixels = to_image(image, "save_image");
        py::gil_scoped_release release;
        if (jpeg_quality)
          save_image(path, pixels, *jpeg_quality);
        else
          save_image(path, pixels);
      },
      py::arg("path"), py::arg("image"), py::kw_only(), py::arg("jpeg_quality") = py::none(),
      "Writes an H x W x C or H x W uint8 array as PNG or JPEG, chosen by the extension (.png, "
      ".jpg, .jpeg; jpeg_quality in [1, 100], None: the library's default); never leaves a partial "
      "file.");
}

}  // namespace

PYBIND11_MODULE(geolens, m) {
  m.doc() =
      "geolens: magnify regions of an image with a geometric focus+context lens.\n\n"
      "Images are H x W x C (or H x W) uint8 arrays; coordinates are source pixels, origin "
      "top-left, y down. Bad input raises ValueError with the message the CLI prints, a failed "
      "solve RuntimeError.";
  m.attr("__version__") = GEOLENS_VERSION;

  bind_lenses(m);
  bind_results(m);

  std::vector<std::string> classic_names;
  for (const ClassicLens kind : kClassicLenses) classic_names.push_back(to_string(kind));
  m.attr("CLASSIC_LENSES") = py::tuple(py::cast(classic_names));

  bind_lens_calls(m);
  bind_image_calls(m);
}
