#pragma once
// geolens in one include: every installed header, layer by layer (docs/architecture.md).
// A program that needs only the lens engine (geolens::lens) includes the headers of core,
// numerics, geometry, warp, measure and lens it uses instead.

/// \namespace geolens
/// Everything geolens declares. Positions are pixels, origin top-left, y down: source pixels in
/// the image a lens magnifies, screen pixels in the output it is shown in; a WarpMesh maps one to
/// the other. Errors are the exceptions of core/errors.h: InvalidInput for what a caller passed,
/// IoError, SolverError and Cancelled for what failed or was stopped at run time.

#include "geolens/core/errors.h"
#include "geolens/core/parse.h"
#include "geolens/core/solve_control.h"
#include "geolens/eval/comparison.h"
#include "geolens/eval/run_stats.h"
#include "geolens/geometry/grid.h"
#include "geolens/geometry/roi.h"
#include "geolens/geometry/subdivide.h"
#include "geolens/io/file_io.h"
#include "geolens/io/geojson.h"
#include "geolens/io/image.h"
#include "geolens/io/mesh_io.h"
#include "geolens/io/point_csv.h"
#include "geolens/io/run_files.h"
#include "geolens/io/vector_data.h"
#include "geolens/lens/classic_lens.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens.h"
#include "geolens/lens/lens_method.h"
#include "geolens/lens/lens_options.h"
#include "geolens/lens/lens_session.h"
#include "geolens/lens/lens_spec.h"
#include "geolens/lens/lens_worker.h"
#include "geolens/measure/distortion.h"
#include "geolens/render/annotate.h"
#include "geolens/render/overlay.h"
#include "geolens/render/render.h"
#include "geolens/render3d/camera.h"
#include "geolens/source/map_style.h"
#include "geolens/source/source.h"
#include "geolens/source/source_file.h"
#include "geolens/warp/map_features.h"
#include "geolens/warp/warp_map.h"
#include "geolens/warp/warp_mesh.h"
