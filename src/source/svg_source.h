#pragma once
// An SVG file as a source, rasterized by librsvg per tile at the resolution each tile is shown
// at, so that a magnified focus shows crisp edges and text rather than blown-up pixels.

#include <string>

#include "geolens/source/source_file.h"

namespace geolens {

/// How much finer than the frame an SVG source's level 0 is: 2^kSvgDetail texels per frame pixel
/// (8), so a lens of zoom up to 8 samples texels drawn at its own resolution.
constexpr int kSvgDetail = 3;

/// Opens the SVG file at `path` (parsed once, by librsvg, at 96 dots per inch, so 1 pt = 4/3 px).
///
/// The frame: options.width x options.height pixels (--size); with only one of them given, the
/// other follows the SVG's aspect ratio; with neither, the SVG's intrinsic size in CSS pixels
/// (its width and height, or else its viewBox), rounded. The whole extent of the SVG (its
/// intrinsic size) is drawn over the whole frame, stretched to the frame's aspect if it differs:
/// an SVG of 432 x 360 pt framed 1024 x 854 has its centre at frame pixel (512, 427).
///
/// The source: RGB, the SVG drawn anti-aliased over opaque white (a transparent SVG shows white,
/// as in a browser); a TiledSource (1024-texel tiles, as librsvg draws the whole document for each,
/// and a 256 MiB cache) whose level 0 is the frame times 2^kSvgDetail (scale = 8) and whose every
/// level is rendered by librsvg + cairo straight at that level's resolution, tile by tile, when a
/// render first needs the tile: opening rasterizes nothing. Thread safety: a librsvg handle must
/// not be used by two threads at once, so tiles are drawn with handles from a pool, each lent to
/// one thread at a time, a new one parsed from the file's bytes (kept in memory) when every handle
/// is busy: at most one per thread that renders at once, so the renderer's threads draw tiles in
/// parallel rather than queue on one handle. (Checked on Debian 12's librsvg 2.54, cairo 1.16,
/// pango 1.50: 4 threads, a handle each, 4800 renders of a text page at varied scales, no failure.
/// timg reported, in 2024, crashes in cairo's FreeType glyph loading when rendering with librsvg on
/// several threads, and serialized its renders; a mutex in the pool would be the fallback.)
///
/// SourceFile::counters: "tiles" (tiles drawn so far), "cache_peak_mb", "svg_handles".
/// Throws InvalidInput("open_svg: '<path>': <what>") when the file cannot be read, librsvg
/// refuses it (with librsvg's message: the line and column of an XML error), it has no size
/// and no --size is given, or a size given is negative or over 16384.
SourceFile open_svg(const std::string& path, const SourceFileOptions& options = {});

}  // namespace geolens
