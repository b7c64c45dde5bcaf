#pragma once
// Exceptions thrown by geolens. They stay on in release builds; every message names the
// function that threw and the offending value.

#include <stdexcept>
#include <string>
#include <string_view>

namespace geolens {

/// The caller passed something invalid: a value out of range, a size mismatch, an unreadable
/// or corrupt input file. The CLI maps it to exit code 2.
struct InvalidInput : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// An option out of range: InvalidInput "<function>: <option> <problem>" that keeps the option,
/// named as the faces name it, words joined by '_' ("mesh_tolerance": the CLI's --mesh-tolerance,
/// Python's mesh_tolerance=), and the problem apart, so that a face says it in its own terms.
struct InvalidOption : InvalidInput {
  /// The message is "<function>: <option> <problem>".
  InvalidOption(const char* function, const std::string& option, const std::string& problem);
  ///@{
  std::string option, problem;  ///< the option as the faces name it, and what is wrong with it
  ///@}
};

/// A numerical failure at run time (a factorization that is not positive definite, ...).
/// The CLI maps it to exit code 1.
struct SolverError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Writing an output failed at run time. The CLI maps it to exit code 1.
struct IoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A long call was stopped through its SolveControl's cancel flag (solve_control.h). Nothing the
/// call would have returned exists; objects it used stay usable.
struct Cancelled : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Throws InvalidInput("<function>: <what>") unless `condition` holds.
void require(bool condition, const char* function, const std::string& what);

/// Throws InvalidOption(function, option, problem) unless `condition` holds.
void require_option(bool condition, const char* function, const std::string& option,
                    const std::string& problem);
/// A line of a user's file as a message quotes it: control characters and bytes outside ASCII
/// written `\xNN` (so none reaches the terminal), cut after 60 characters with its length said
/// ("...(52000000 characters)").
std::string quoted_line(std::string_view line);
/// `value` for a message: the shortest text that reads back to it (180.00000000000014, 1e-09,
/// not std::to_string's rounded 180.000000 and 0.000000).
std::string number_text(double value);

}  // namespace geolens
