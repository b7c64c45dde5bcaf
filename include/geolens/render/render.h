#pragma once
// CPU renderer: draws a WarpMesh, sampling a Source (an image's mip pyramid, a tiled image, ...).

#include <array>
#include <cstdint>

#include "geolens/io/image.h"
#include "geolens/source/source.h"  // the usual source; callers build it next to render()
#include "geolens/source/source.h"
#include "geolens/source/source_file.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens {

class ThreadPool;  // core/thread_pool.h

/// What render() draws: the output's size and background, how it samples the source's levels,
/// and on which threads.
struct RenderOptions {
  int width = 0;                                             ///< output width, pixels (> 0)
  int height = 0;                                            ///< output height, pixels (> 0)
  std::array<uint8_t, 4> background = {255, 255, 255, 255};  ///< for pixels no triangle covers
  /// Texels of source level 0 per unit of the mesh's source coordinates, > 0: 1 when the mesh is
  /// in source pixels; SourceFile::scale for a source finer than the frame the lens was solved in
  /// (source/source_file.h), so a magnified triangle samples the finer levels.
  double source_scale = 1;
  /// The width, in levels (octaves of magnification), of the band across which two neighbouring
  /// levels are blended, in (0, 1]: 1 blends all the way from one level to the next (trilinear,
  /// as texture hardware does: best for photographs); a narrower band shows one level alone
  /// except within band / 2 of the midway point, so text and lines that a level draws at its own
  /// size (map labels, a web map's tiles) show twice only there (SourceFile::level_band).
  double level_band = 1;
  /// threads of the pool render() starts for the call when `pool` is null, the calling thread
  /// included: 0 = hardware concurrency, >= 0
  int threads = 0;
  /// The threads to render on, kept by the caller across calls (a viewer's, so no thread is
  /// started per frame; `threads` is then ignored); null: a pool of `threads` for this call.
  ThreadPool* pool = nullptr;
};

/// Rasterizes the screen triangles of `mesh` (screen coordinates scaled from
/// mesh.screen_width x mesh.screen_height to options.width x options.height) and samples the
/// source at the interpolated source coordinate. The level of detail is chosen per triangle
/// from its screen -> source Jacobian, so a minified context does not alias and a magnified
/// focus is smooth. The output has the source's channel count. Coverage is exact (vertices
/// snapped to 1/256 pixel, a top-left style tie rule), so a pixel on an edge shared by two
/// triangles is drawn once; where triangles overlap (a folded map), the later one in F is on top,
/// whatever the thread count. Texels are blended with 8-bit weights, as texture hardware does.
/// The source is read through Source::fetch, one region per triangle and screen block of at
/// most 64 rows x 256 columns (the texels that block can reach, clamped to the level), from
/// the worker threads at once; so every source renders alike, and an in-memory MipPyramid
/// costs no copy.
Image render(const WarpMesh& mesh, const Source& source, const RenderOptions& options);

/// `warp` (its source in frame pixels) rendered from `file` as every tool shows it: from
/// file.source at file.scale and file.level_band (which replace those of `options`) at
/// options.width x options.height, then file.overlay drawn over it (the output made RGB first).
/// Throws as render() does.
Image render(const WarpMesh& warp, const SourceFile& file, RenderOptions options);

}  // namespace geolens
