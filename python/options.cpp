#include "options.h"

#include <algorithm>
#include <string>

#include "geolens/core/errors.h"
#include "geolens/lens/lens_options.h"

namespace geolens::python {

namespace {

// A keyword's Python type, as its messages name it, and whether `value` has it (bool is not an
// int here).
const char* python_type(LensOptionField::Type type) {
  switch (type) {
    case LensOptionField::Type::kInteger:
      return "int";
    case LensOptionField::Type::kNumber:
      return "float";
    case LensOptionField::Type::kChoice:
      break;
  }
  return "str";
}

bool has_type(const py::handle& value, LensOptionField::Type type) {
  const bool integer = py::isinstance<py::int_>(value) && !py::isinstance<py::bool_>(value);
  switch (type) {
    case LensOptionField::Type::kInteger:
      return integer;
    case LensOptionField::Type::kNumber:
      return integer || py::isinstance<py::float_>(value);
    case LensOptionField::Type::kChoice:
      break;
  }
  return py::isinstance<py::str>(value);
}

// `value` (of the field's type) as the text the field reads.
std::string field_text(const py::handle& value, LensOptionField::Type type) {
  if (type == LensOptionField::Type::kChoice) return value.cast<std::string>();
  if (type == LensOptionField::Type::kInteger) return py::str(value);
  return number_text(value.cast<double>());
}

std::string option_names() {
  std::string names;
  for (const LensOptionField& field : lens_option_fields())
    names += (names.empty() ? "" : ", ") + field.name;
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
    const auto& fields = lens_option_fields();
    const auto field = std::find_if(fields.begin(), fields.end(),
                                    [&](const LensOptionField& f) { return f.name == name; });
    if (field == fields.end())
      throw py::type_error(std::string(function) + "() got an unexpected keyword argument '" +
                           name + "' (options: " + option_names() + ")");
    if (!has_type(value, field->type))
      throw py::type_error(std::string(function) + "(): " + name + " must be " +
                           python_type(field->type) + ", got " + std::string(py::repr(value)));
    try {
      field->set(options, field_text(value, field->type));
    } catch (const InvalidOption& e) {
      throw InvalidInput(std::string(function) + "(): " + e.option + " " + e.problem);
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
  for (const LensOptionField& field : lens_option_fields()) {
    const std::string value = field.get(defaults);
    const bool choice = field.type == LensOptionField::Type::kChoice;
    doc += "    " + field.name + "=" + (choice ? "'" + value + "'" : value) + "\n";
  }
  return doc;
}

std::vector<Lens> to_lenses(const py::handle& lenses, const char* function) {
  std::vector<Lens> list;
  append(lenses, 0, function, list);
  require(!list.empty(), function, "lenses is empty: give at least one lens");
  return list;
}

}  // namespace geolens::python
