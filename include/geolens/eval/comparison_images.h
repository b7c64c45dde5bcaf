#pragma once
// The pictures of a comparison (comparison.h): each method's output and shape-distortion
// heat map, and the panel of every method side by side around the lenses.

#include <string>

#include "geolens/eval/comparison.h"
#include "geolens/io/image.h"
#include "geolens/render/render.h"
#include "geolens/source/source_file.h"

namespace geolens {

/// The panel tile side must be in [64, 1024] pixels; throws InvalidInput naming `function`.
void require_panel_tile(int tile, const char* function);

/// The method's output: its warp rendered from `source` (the comparison's, framed at its size;
/// render(WarpMesh, SourceFile, RenderOptions)) at the comparison's size, RGB.
Image comparison_output(const Comparison& comparison, const ComparedMethod& method,
                        const SourceFile& source);

/// The method's shape distortion s1 / s2 - 1 per triangle over `output` (comparison_output),
/// blue 0 to red `heat_max` (> 0), flipped triangles black, with a scale titled
/// "NAME: shape distortion s1/s2 - 1" below (heatmap.h): RGB, the output's width, taller.
Image comparison_heatmap(const ComparedMethod& method, const Image& output, double heat_max);

/// The input (lenses outlined, a few notes below), then every method: a cell each with four label
/// lines (name, zoom at the first lens, largest shape distortion, area hidden and flips), its
/// output and its heat map below (tile x tile each); four cells per row, the colour scale
/// (0 to `heat_max`, > 0) below. Every picture shows the same square, 1.3 times the extent of the
/// targets' disks. RGB, 4 (tile + 6) + 6 pixels wide; rows = ceil((methods + 1) / 4) of
/// 4 L + 2 tile + 24 pixels (L = 22 for tile >= 176, else 11), plus 6 pixels and the scale.
/// `source` as for comparison_output. Throws InvalidInput for `tile` outside [64, 1024].
Image comparison_panel(const Comparison& comparison, const SourceFile& source, double heat_max,
                       int tile = 256);

}  // namespace geolens
