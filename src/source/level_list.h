#pragma once
// An image pyramid given as a list of image files of one extent at growing resolution.

#include <cstddef>
#include <string>
#include <vector>

#include "geolens/source/source_file.h"

namespace geolens {

/// Opens a level list: a text file (".levels" by convention) naming one image (PNG or JPEG) per
/// line, relative to the list's folder unless absolute. Blank lines and lines whose first
/// non-blank character is '#' are ignored; leading and trailing blanks are trimmed.
///
/// The rules, checked from the images' headers when the list is opened:
/// - the images may come in any order; the widest is the finest, source level 0 (W x H);
/// - every other image is that level halved k >= 1 times: its width is W / 2^k rounded up or
///   down, and its height H / 2^k rounded the same way or the other (the Source's level k is
///   the rounded-up size; an image one texel short repeats its last column or row). An image
///   whose width is no such size is refused, and so is one whose height does not match the k its
///   width gives (the extents, or the aspect ratios, disagree), naming its line;
/// - two images of the same level are refused, naming both lines;
/// - the levels between the given ones are made by downsampling the next finer level
///   (downsample.h), when first needed;
/// - the source has the channel count of the coarsest image (decoded when the list is opened);
///   the other images are converted to it (source/convert_channels rules: grey <-> RGB by luma,
///   alpha added as 255 or dropped).
///
/// Lazy: an image is decoded the first time a fetch needs its level (or a level made from it),
/// and kept, with the levels made from it, in a least-recently-used cache of whole levels of at
/// most `cache_bytes` texel bytes (the level in use is kept even when it alone is larger), so
/// memory stays bounded whatever the list holds; an evicted level is decoded or made again.
///
/// Frame: the coarsest image's size, or, when options.width (or else options.height) is > 0,
/// the level (given or made) whose width (height) is nearest to it by ratio; `scale` = W / frame
/// width, a power of two. kind "level list"; counters {"images_decoded", n} (files decoded,
/// again after an eviction) and {"levels_made", n} (levels downsampled).
///
/// Throws InvalidInput naming "open_level_list", the list file and, for an image, its line
/// number and path: an unreadable list, a list without images, an image that is missing or not
/// a PNG or JPEG, the size rules above. A fetch throws InvalidInput naming the image when it
/// fails to decode or its decoded size is not its header's.
SourceFile open_level_list(const std::string& path, const SourceFileOptions& options = {},
                           size_t cache_bytes = size_t(1) << 30);

/// The images the level list at `path` names, in its order, each resolved against the list's
/// folder (the paths open_level_list reads); empty if the list cannot be read. For the checks a
/// tool makes before its work: every one is an input.
std::vector<std::string> level_list_images(const std::string& path);

}  // namespace geolens
