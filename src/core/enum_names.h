#pragma once
// Private: an enum named by one table of {value, name} pairs, which gives both directions: the
// name of a value, and the value of a name with the one error every parser of the library gives,
// "FUNCTION: unknown WHAT 'NAME' (expected A, B or C)", the names in the table's order.

#include <cstddef>
#include <string>

#include "geolens/core/errors.h"

namespace geolens {

template <class Enum>
struct EnumName {
  Enum value;
  const char* name;
};

/// The table's names as a message lists them: "A, B or C".
template <class Enum, std::size_t N>
std::string enum_list(const EnumName<Enum> (&table)[N]) {
  std::string names;
  for (std::size_t i = 0; i < N; ++i)
    names += std::string(i == 0 ? "" : i + 1 == N ? " or " : ", ") + table[i].name;
  return names;
}

template <class Enum, std::size_t N>
Enum parse_enum(const EnumName<Enum> (&table)[N], const std::string& name, const char* function,
                const char* what) {
  for (const EnumName<Enum>& entry : table)
    if (name == entry.name) return entry.value;
  throw InvalidInput(std::string(function) + ": unknown " + what + " '" + name + "' (expected " +
                     enum_list(table) + ")");
}

template <class Enum, std::size_t N>
std::string enum_name(const EnumName<Enum> (&table)[N], Enum value) {
  for (const EnumName<Enum>& entry : table)
    if (entry.value == value) return entry.name;
  return "?";
}

}  // namespace geolens
