#pragma once
// The lens options shared by every geolens subcommand that places lenses.

#include <CLI/CLI.hpp>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/core/parse.h"
#include "geolens/io/image.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens_options.h"
#include "geolens/lens/lens_spec.h"

namespace geolens::cli {

/// The raw command-line values; parse() turns them into lenses and options.
struct LensArgs {
  std::vector<std::string> lenses;
  double zoom = 2.0;
  std::string profile = "gaussian";
  double footprint = 0;
  /// The solver's options as given, by name (lens_option_fields, lens/lens_options.h), each
  /// starting as its default's text.
  std::map<std::string, std::string> options;
};

/// Registers --lens (required), --zoom, --profile, --footprint and every field of
/// lens_option_fields() but draft_mesh (a session's; the CLI solves once) as --NAME, its help
/// and default from the table, on `command`.
void add_lens_options(CLI::App& command, LensArgs& args);

/// What `work` returns; an InvalidOption it throws (core/errors.h) is rethrown as InvalidInput
/// in the CLI's words, `context` after it: "--mesh-tolerance: must be ...".
template <class Work>
auto naming_options(Work work, const std::string& context = "") {
  try {
    return work();
  } catch (const InvalidOption& e) {
    throw InvalidInput(option_flag(e.option) + ": " + e.problem + context);
  }
}

/// The solver options; throws InvalidInput for an unknown name or a value out of range.
LensOptions parse_options(const LensArgs& args);

/// The lenses of every --lens value (parse_lens_spec, lens/lens_spec.h), validated against a
/// source of width x height pixels. Throws InvalidInput naming the offending value.
std::vector<Lens> parse_lenses(const LensArgs& args, int width, int height);
/// parse_lenses against the size of `source`.
std::vector<Lens> parse_lenses(const LensArgs& args, const Image& source);

/// The files of the polygon:FILE and mask:FILE lenses, read from the values alone (a malformed
/// value is left to parse_lenses to reject).
std::vector<LensSpecFile> lens_files(const LensArgs& args);

constexpr int kMaxSide = 16384;  ///< the largest side --size takes, pixels

/// Prints a warning on stderr for each option set that the model solving `lenses` does not read
/// (unread_options, lens/lens_options.h).
void warn_about_unread_options(const LensOptions& options, const std::vector<Lens>& lenses);

/// Prints a warning on stderr for each lens that does not fit where it is (the largest zoom
/// that fits, for the focus model) or misses its requested zoom by more than 10 %.
void warn_about_zooms(const std::vector<Lens>& lenses, const LensResult& result);

}  // namespace geolens::cli
