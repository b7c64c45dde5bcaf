#include "options.h"

#include <sstream>
#include <string>

#include "geolens/core/errors.h"
#include "geolens/lens/lens_options.h"

namespace geolens::python {

namespace {

// One keyword: how it sets the options and how its value reads (for the docstring).
struct Option {
  const char* name;
  const char* type;  // for messages: "str", "int" or "float"
  void (*set)(LensOptions&, const py::handle&);
  std::string (*show)(const LensOptions&);
};

std::string number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string quoted(const std::string& name) { return "'" + name + "'"; }

const Option kOptions[] = {
    {"model", "str",
     [](LensOptions& o, const py::handle& v) { o.model = parse_lens_model(v.cast<std::string>()); },
     [](const LensOptions& o) { return quoted(to_string(o.model)); }},
    {"mesh", "int", [](LensOptions& o, const py::handle& v) { o.mesh = v.cast<int>(); },
     [](const LensOptions& o) { return number(o.mesh); }},
    {"mesh_tolerance", "float",
     [](LensOptions& o, const py::handle& v) { o.mesh_tolerance = v.cast<double>(); },
     [](const LensOptions& o) { return number(o.mesh_tolerance); }},
    {"draft_mesh", "int", [](LensOptions& o, const py::handle& v) { o.draft_mesh = v.cast<int>(); },
     [](const LensOptions& o) { return number(o.draft_mesh); }},
    {"subdivide", "int",
     [](LensOptions& o, const py::handle& v) { o.subdivision.max_levels = v.cast<int>(); },
     [](const LensOptions& o) { return number(o.subdivision.max_levels); }},
    {"metric", "str",
     [](LensOptions& o, const py::handle& v) {
       o.flatten.metric = parse_metric(v.cast<std::string>());
     },
     [](const LensOptions& o) { return quoted(to_string(o.flatten.metric)); }},
    {"alpha", "float",
     [](LensOptions& o, const py::handle& v) { o.flatten.alpha = v.cast<double>(); },
     [](const LensOptions& o) { return number(o.flatten.alpha); }},
    {"weights", "str",
     [](LensOptions& o, const py::handle& v) {
       o.flatten.weights = parse_flatten_weights(v.cast<std::string>());
     },
     [](const LensOptions& o) { return quoted(to_string(o.flatten.weights)); }},
    {"texture", "str",
     [](LensOptions& o, const py::handle& v) {
       o.texture = parse_texture_weights(v.cast<std::string>());
     },
     [](const LensOptions& o) { return quoted(to_string(o.texture)); }},
    {"boundary", "str",
     [](LensOptions& o, const py::handle& v) {
       o.flatten.boundary = parse_boundary(v.cast<std::string>());
     },
     [](const LensOptions& o) { return quoted(to_string(o.flatten.boundary)); }},
    {"extent", "str",
     [](LensOptions& o, const py::handle& v) { o.extent = parse_extent(v.cast<std::string>()); },
     [](const LensOptions& o) { return quoted(to_string(o.extent)); }},
    {"extent_factor", "float",
     [](LensOptions& o, const py::handle& v) { o.extent_factor = v.cast<double>(); },
     [](const LensOptions& o) { return number(o.extent_factor); }},
    {"tolerance", "float",
     [](LensOptions& o, const py::handle& v) { o.flatten.tolerance = v.cast<double>(); },
     [](const LensOptions& o) { return number(o.flatten.tolerance); }},
    {"max_iterations", "int",
     [](LensOptions& o, const py::handle& v) { o.flatten.max_iterations = v.cast<int>(); },
     [](const LensOptions& o) { return number(o.flatten.max_iterations); }},
    {"threads", "int",
     [](LensOptions& o, const py::handle& v) { o.flatten.threads = v.cast<int>(); },
     [](const LensOptions& o) { return number(o.flatten.threads); }},
};

std::string option_names() {
  std::string names;
  for (const Option& option : kOptions)
    names += (names.empty() ? "" : ", ") + std::string(option.name);
  return names;
}

void append(const py::handle& item, int depth, const char* function, std::vector<Lens>& lenses) {
  if (py::isinstance<Lens>(item)) {
    lenses.push_back(item.cast<Lens>());
    return;
  }
  require(depth < 2 && py::isinstance<py::sequence>(item) && !py::isinstance<py::str>(item),
          function,
          "lenses must be a Lens or a list of them (circle(), polygon(), mask()), got " +
              std::string(py::repr(item)));
  for (const py::handle& element : py::reinterpret_borrow<py::sequence>(item))
    append(element, depth + 1, function, lenses);
}

}  // namespace

LensOptions lens_options(const py::kwargs& kwargs, const char* function) {
  LensOptions options;
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    const Option* option = nullptr;
    for (const Option& o : kOptions)
      if (name == o.name) option = &o;
    if (!option)
      throw py::type_error(std::string(function) + "() got an unexpected keyword argument '" +
                           name + "' (options: " + option_names() + ")");
    try {
      option->set(options, value);
    } catch (const py::cast_error&) {
      throw py::type_error(std::string(function) + "(): " + name + " must be " + option->type +
                           ", got " + std::string(py::repr(value)));
    }
  }
  try {
    validate(options);
  } catch (const InvalidOption& e) {  // in Python's words: the keyword, then what is wrong
    throw InvalidInput(std::string(function) + "(): " + e.option + " " + e.problem);
  }
  return options;
}

std::string lens_options_doc() {
  const LensOptions defaults;
  std::string doc;
  for (const Option& option : kOptions)
    doc += "    " + std::string(option.name) + "=" + option.show(defaults) + "\n";
  return doc;
}

std::vector<Lens> to_lenses(const py::handle& lenses, const char* function) {
  std::vector<Lens> list;
  append(lenses, 0, function, list);
  require(!list.empty(), function, "lenses is empty: give at least one lens");
  return list;
}

}  // namespace geolens::python
