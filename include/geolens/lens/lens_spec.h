#pragma once
// Lenses written as text, the form the CLI's --lens takes (and the viewer and Python next):
// `circle:CX,CY,R[:ZOOM]` (source pixels), `polygon:FILE[:ZOOM]` (one 'x y' vertex per line) or
// `mask:FILE[:ZOOM]` (an image of the source's size; each 8-connected blob of non-zero pixels,
// at the file's bit depth, is one lens).

#include <optional>
#include <string>
#include <vector>

#include "geolens/lens/lens.h"

namespace geolens {

/// The syntax, for messages: "circle:CX,CY,R[:ZOOM], polygon:FILE[:ZOOM] or mask:FILE[:ZOOM]".
extern const char* const kLensSpecSyntax;

/// How far a polygon file's outline may move when it is simplified (simplify_loop), pixels.
inline constexpr double kPolygonTolerance = 0.1;

/// The lenses `spec` names (several for a mask of several blobs), each with the spec's zoom or
/// `default_zoom`, `profile` and `footprint`, validated for a width x height source
/// (validate_lens). Reads the polygon or mask file; a polygon's vertices are simplified to
/// kPolygonTolerance (read_polygon_file, simplify_loop). A mask's blobs of fewer than
/// Region::kMinMaskBlobPixels pixels are left out, said in one line added to `warnings` if given.
/// Throws InvalidInput naming the spec and what is wrong with it.
std::vector<Lens> parse_lens_spec(const std::string& spec, double default_zoom, Profile profile,
                                  double footprint, int width, int height,
                                  std::vector<std::string>* warnings = nullptr);

/// A file a spec reads: `kind` "polygon" or "mask", `path` its FILE.
struct LensSpecFile {
  ///@{
  std::string kind, path;  ///< "polygon" or "mask"; the FILE as the spec writes it
  ///@}
};
/// The file `spec` reads, from the text alone (none for a circle or a malformed spec, which
/// parse_lens_spec rejects): so a tool can check its outputs against it before any work.
std::optional<LensSpecFile> lens_spec_file(const std::string& spec);

}  // namespace geolens
