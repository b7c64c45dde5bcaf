// make_scene_examples: writes the 3D inputs of the README's "3D inputs" section and of
// docs/reproduction.md (the paper's Fig. 3 and Fig. 8) into a folder:
//
//   teapot.obj    the Utah teapot, tessellated from its 32 bicubic Bezier patches (306 control
//                 points); STEPS x STEPS quads per patch (default 33: 69,432 triangles), patches
//                 welded into one smooth mesh, +Y up, the spout towards +X
//   phantom.nrrd  a 160^3 CT-like head phantom, int16 in Hounsfield-like units, gzip: a skull
//                 with its upper front quarter cut away, and inside it a tree of contrast-filled
//                 vessels thinning to about one voxel, an aneurysm, a tumour with calcified specks,
//                 two ventricles and a calcification (`--transfer ct` shows them)
//
// Usage: make_scene_examples OUTPUT_FOLDER [STEPS]   (STEPS in [1, 200])
// Exit code 0 on success, 1 if a file cannot be written, 2 on bad usage.
//
// Deterministic: the vessel tree's random choices come from a std::mt19937 with a fixed seed.
// Both files are read back with geolens's own readers (load_obj, load_nrrd) before it reports.

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "render3d/nrrd_file.h"
#include "render3d/obj_file.h"

namespace {

struct Vec3 {
  double x, y, z;
};
Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double norm(Vec3 a) { return std::sqrt(dot(a, a)); }

// ---------------------------------------------------------------------------------------------
// The Utah teapot: Martin Newell's data (University of Utah, 1975), as published by Frank Crow,
// "The Origins of the Teapot", IEEE Computer Graphics and Applications 7(1), 1987, pp. 8-19:
// 32 bicubic Bezier patches (rim 4, body 8, handle 4, spout 4, lid 8, bottom 4) over 306 control
// points, z up. Each patch lists its 4 x 4 control points, 1-based, row by row. Checked against
// the independent copy in Debian's asymptote-doc (examples/teapot.asy, scaled by 72 / 2.54).

constexpr int kPatches[32][16] = {
    // rim
    {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16},
    {4, 17, 18, 19, 8, 20, 21, 22, 12, 23, 24, 25, 16, 26, 27, 28},
    {19, 29, 30, 31, 22, 32, 33, 34, 25, 35, 36, 37, 28, 38, 39, 40},
    {31, 41, 42, 1, 34, 43, 44, 5, 37, 45, 46, 9, 40, 47, 48, 13},
    // body
    {13, 14, 15, 16, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60},
    {16, 26, 27, 28, 52, 61, 62, 63, 56, 64, 65, 66, 60, 67, 68, 69},
    {28, 38, 39, 40, 63, 70, 71, 72, 66, 73, 74, 75, 69, 76, 77, 78},
    {40, 47, 48, 13, 72, 79, 80, 49, 75, 81, 82, 53, 78, 83, 84, 57},
    {57, 58, 59, 60, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96},
    {60, 67, 68, 69, 88, 97, 98, 99, 92, 100, 101, 102, 96, 103, 104, 105},
    {69, 76, 77, 78, 99, 106, 107, 108, 102, 109, 110, 111, 105, 112, 113, 114},
    {78, 83, 84, 57, 108, 115, 116, 85, 111, 117, 118, 89, 114, 119, 120, 93},
    // handle
    {121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135, 136},
    {124, 137, 138, 121, 128, 139, 140, 125, 132, 141, 142, 129, 136, 143, 144, 133},
    {133, 134, 135, 136, 145, 146, 147, 148, 149, 150, 151, 152, 69, 153, 154, 155},
    {136, 143, 144, 133, 148, 156, 157, 145, 152, 158, 159, 149, 155, 160, 161, 69},
    // spout
    {162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175, 176, 177},
    {165, 178, 179, 162, 169, 180, 181, 166, 173, 182, 183, 170, 177, 184, 185, 174},
    {174, 175, 176, 177, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 196, 197},
    {177, 184, 185, 174, 189, 198, 199, 186, 193, 200, 201, 190, 197, 202, 203, 194},
    // lid
    {204, 204, 204, 204, 207, 208, 209, 210, 211, 211, 211, 211, 212, 213, 214, 215},
    {204, 204, 204, 204, 210, 217, 218, 219, 211, 211, 211, 211, 215, 220, 221, 222},
    {204, 204, 204, 204, 219, 224, 225, 226, 211, 211, 211, 211, 222, 227, 228, 229},
    {204, 204, 204, 204, 226, 230, 231, 207, 211, 211, 211, 211, 229, 232, 233, 212},
    {212, 213, 214, 215, 234, 235, 236, 237, 238, 239, 240, 241, 242, 243, 244, 245},
    {215, 220, 221, 222, 237, 246, 247, 248, 241, 249, 250, 251, 245, 252, 253, 254},
    {222, 227, 228, 229, 248, 255, 256, 257, 251, 258, 259, 260, 254, 261, 262, 263},
    {229, 232, 233, 212, 257, 264, 265, 234, 260, 266, 267, 238, 263, 268, 269, 242},
    // bottom
    {270, 270, 270, 270, 279, 280, 281, 282, 275, 276, 277, 278, 271, 272, 273, 274},
    {270, 270, 270, 270, 282, 289, 290, 291, 278, 286, 287, 288, 274, 283, 284, 285},
    {270, 270, 270, 270, 291, 298, 299, 300, 288, 295, 296, 297, 285, 292, 293, 294},
    {270, 270, 270, 270, 300, 305, 306, 279, 297, 303, 304, 275, 294, 301, 302, 271},
};

constexpr double kPoints[306][3] = {
    {1.4, 0.0, 2.4},
    {1.4, -0.784, 2.4},
    {0.784, -1.4, 2.4},
    {0.0, -1.4, 2.4},
    {1.3375, 0.0, 2.53125},
    {1.3375, -0.749, 2.53125},
    {0.749, -1.3375, 2.53125},
    {0.0, -1.3375, 2.53125},
    {1.4375, 0.0, 2.53125},
    {1.4375, -0.805, 2.53125},
    {0.805, -1.4375, 2.53125},
    {0.0, -1.4375, 2.53125},
    {1.5, 0.0, 2.4},
    {1.5, -0.84, 2.4},
    {0.84, -1.5, 2.4},
    {0.0, -1.5, 2.4},
    {-0.784, -1.4, 2.4},
    {-1.4, -0.784, 2.4},
    {-1.4, 0.0, 2.4},
    {-0.749, -1.3375, 2.53125},
    {-1.3375, -0.749, 2.53125},
    {-1.3375, 0.0, 2.53125},
    {-0.805, -1.4375, 2.53125},
    {-1.4375, -0.805, 2.53125},
    {-1.4375, 0.0, 2.53125},
    {-0.84, -1.5, 2.4},
    {-1.5, -0.84, 2.4},
    {-1.5, 0.0, 2.4},
    {-1.4, 0.784, 2.4},
    {-0.784, 1.4, 2.4},
    {0.0, 1.4, 2.4},
    {-1.3375, 0.749, 2.53125},
    {-0.749, 1.3375, 2.53125},
    {0.0, 1.3375, 2.53125},
    {-1.4375, 0.805, 2.53125},
    {-0.805, 1.4375, 2.53125},
    {0.0, 1.4375, 2.53125},
    {-1.5, 0.84, 2.4},
    {-0.84, 1.5, 2.4},
    {0.0, 1.5, 2.4},
    {0.784, 1.4, 2.4},
    {1.4, 0.784, 2.4},
    {0.749, 1.3375, 2.53125},
    {1.3375, 0.749, 2.53125},
    {0.805, 1.4375, 2.53125},
    {1.4375, 0.805, 2.53125},
    {0.84, 1.5, 2.4},
    {1.5, 0.84, 2.4},
    {1.75, 0.0, 1.875},
    {1.75, -0.98, 1.875},
    {0.98, -1.75, 1.875},
    {0.0, -1.75, 1.875},
    {2.0, 0.0, 1.35},
    {2.0, -1.12, 1.35},
    {1.12, -2.0, 1.35},
    {0.0, -2.0, 1.35},
    {2.0, 0.0, 0.9},
    {2.0, -1.12, 0.9},
    {1.12, -2.0, 0.9},
    {0.0, -2.0, 0.9},
    {-0.98, -1.75, 1.875},
    {-1.75, -0.98, 1.875},
    {-1.75, 0.0, 1.875},
    {-1.12, -2.0, 1.35},
    {-2.0, -1.12, 1.35},
    {-2.0, 0.0, 1.35},
    {-1.12, -2.0, 0.9},
    {-2.0, -1.12, 0.9},
    {-2.0, 0.0, 0.9},
    {-1.75, 0.98, 1.875},
    {-0.98, 1.75, 1.875},
    {0.0, 1.75, 1.875},
    {-2.0, 1.12, 1.35},
    {-1.12, 2.0, 1.35},
    {0.0, 2.0, 1.35},
    {-2.0, 1.12, 0.9},
    {-1.12, 2.0, 0.9},
    {0.0, 2.0, 0.9},
    {0.98, 1.75, 1.875},
    {1.75, 0.98, 1.875},
    {1.12, 2.0, 1.35},
    {2.0, 1.12, 1.35},
    {1.12, 2.0, 0.9},
    {2.0, 1.12, 0.9},
    {2.0, 0.0, 0.45},
    {2.0, -1.12, 0.45},
    {1.12, -2.0, 0.45},
    {0.0, -2.0, 0.45},
    {1.5, 0.0, 0.225},
    {1.5, -0.84, 0.225},
    {0.84, -1.5, 0.225},
    {0.0, -1.5, 0.225},
    {1.5, 0.0, 0.15},
    {1.5, -0.84, 0.15},
    {0.84, -1.5, 0.15},
    {0.0, -1.5, 0.15},
    {-1.12, -2.0, 0.45},
    {-2.0, -1.12, 0.45},
    {-2.0, 0.0, 0.45},
    {-0.84, -1.5, 0.225},
    {-1.5, -0.84, 0.225},
    {-1.5, 0.0, 0.225},
    {-0.84, -1.5, 0.15},
    {-1.5, -0.84, 0.15},
    {-1.5, 0.0, 0.15},
    {-2.0, 1.12, 0.45},
    {-1.12, 2.0, 0.45},
    {0.0, 2.0, 0.45},
    {-1.5, 0.84, 0.225},
    {-0.84, 1.5, 0.225},
    {0.0, 1.5, 0.225},
    {-1.5, 0.84, 0.15},
    {-0.84, 1.5, 0.15},
    {0.0, 1.5, 0.15},
    {1.12, 2.0, 0.45},
    {2.0, 1.12, 0.45},
    {0.84, 1.5, 0.225},
    {1.5, 0.84, 0.225},
    {0.84, 1.5, 0.15},
    {1.5, 0.84, 0.15},
    {-1.6, 0.0, 2.025},
    {-1.6, -0.3, 2.025},
    {-1.5, -0.3, 2.25},
    {-1.5, 0.0, 2.25},
    {-2.3, 0.0, 2.025},
    {-2.3, -0.3, 2.025},
    {-2.5, -0.3, 2.25},
    {-2.5, 0.0, 2.25},
    {-2.7, 0.0, 2.025},
    {-2.7, -0.3, 2.025},
    {-3.0, -0.3, 2.25},
    {-3.0, 0.0, 2.25},
    {-2.7, 0.0, 1.8},
    {-2.7, -0.3, 1.8},
    {-3.0, -0.3, 1.8},
    {-3.0, 0.0, 1.8},
    {-1.5, 0.3, 2.25},
    {-1.6, 0.3, 2.025},
    {-2.5, 0.3, 2.25},
    {-2.3, 0.3, 2.025},
    {-3.0, 0.3, 2.25},
    {-2.7, 0.3, 2.025},
    {-3.0, 0.3, 1.8},
    {-2.7, 0.3, 1.8},
    {-2.7, 0.0, 1.575},
    {-2.7, -0.3, 1.575},
    {-3.0, -0.3, 1.35},
    {-3.0, 0.0, 1.35},
    {-2.5, 0.0, 1.125},
    {-2.5, -0.3, 1.125},
    {-2.65, -0.3, 0.9375},
    {-2.65, 0.0, 0.9375},
    {-2.0, -0.3, 0.9},
    {-1.9, -0.3, 0.6},
    {-1.9, 0.0, 0.6},
    {-3.0, 0.3, 1.35},
    {-2.7, 0.3, 1.575},
    {-2.65, 0.3, 0.9375},
    {-2.5, 0.3, 1.125},
    {-1.9, 0.3, 0.6},
    {-2.0, 0.3, 0.9},
    {1.7, 0.0, 1.425},
    {1.7, -0.66, 1.425},
    {1.7, -0.66, 0.6},
    {1.7, 0.0, 0.6},
    {2.6, 0.0, 1.425},
    {2.6, -0.66, 1.425},
    {3.1, -0.66, 0.825},
    {3.1, 0.0, 0.825},
    {2.3, 0.0, 2.1},
    {2.3, -0.25, 2.1},
    {2.4, -0.25, 2.025},
    {2.4, 0.0, 2.025},
    {2.7, 0.0, 2.4},
    {2.7, -0.25, 2.4},
    {3.3, -0.25, 2.4},
    {3.3, 0.0, 2.4},
    {1.7, 0.66, 0.6},
    {1.7, 0.66, 1.425},
    {3.1, 0.66, 0.825},
    {2.6, 0.66, 1.425},
    {2.4, 0.25, 2.025},
    {2.3, 0.25, 2.1},
    {3.3, 0.25, 2.4},
    {2.7, 0.25, 2.4},
    {2.8, 0.0, 2.475},
    {2.8, -0.25, 2.475},
    {3.525, -0.25, 2.49375},
    {3.525, 0.0, 2.49375},
    {2.9, 0.0, 2.475},
    {2.9, -0.15, 2.475},
    {3.45, -0.15, 2.5125},
    {3.45, 0.0, 2.5125},
    {2.8, 0.0, 2.4},
    {2.8, -0.15, 2.4},
    {3.2, -0.15, 2.4},
    {3.2, 0.0, 2.4},
    {3.525, 0.25, 2.49375},
    {2.8, 0.25, 2.475},
    {3.45, 0.15, 2.5125},
    {2.9, 0.15, 2.475},
    {3.2, 0.15, 2.4},
    {2.8, 0.15, 2.4},
    {0.0, 0.0, 3.15},
    {0.0, -0.002, 3.15},
    {0.002, 0.0, 3.15},
    {0.8, 0.0, 3.15},
    {0.8, -0.45, 3.15},
    {0.45, -0.8, 3.15},
    {0.0, -0.8, 3.15},
    {0.0, 0.0, 2.85},
    {0.2, 0.0, 2.7},
    {0.2, -0.112, 2.7},
    {0.112, -0.2, 2.7},
    {0.0, -0.2, 2.7},
    {-0.002, 0.0, 3.15},
    {-0.45, -0.8, 3.15},
    {-0.8, -0.45, 3.15},
    {-0.8, 0.0, 3.15},
    {-0.112, -0.2, 2.7},
    {-0.2, -0.112, 2.7},
    {-0.2, 0.0, 2.7},
    {0.0, 0.002, 3.15},
    {-0.8, 0.45, 3.15},
    {-0.45, 0.8, 3.15},
    {0.0, 0.8, 3.15},
    {-0.2, 0.112, 2.7},
    {-0.112, 0.2, 2.7},
    {0.0, 0.2, 2.7},
    {0.45, 0.8, 3.15},
    {0.8, 0.45, 3.15},
    {0.112, 0.2, 2.7},
    {0.2, 0.112, 2.7},
    {0.4, 0.0, 2.55},
    {0.4, -0.224, 2.55},
    {0.224, -0.4, 2.55},
    {0.0, -0.4, 2.55},
    {1.3, 0.0, 2.55},
    {1.3, -0.728, 2.55},
    {0.728, -1.3, 2.55},
    {0.0, -1.3, 2.55},
    {1.3, 0.0, 2.4},
    {1.3, -0.728, 2.4},
    {0.728, -1.3, 2.4},
    {0.0, -1.3, 2.4},
    {-0.224, -0.4, 2.55},
    {-0.4, -0.224, 2.55},
    {-0.4, 0.0, 2.55},
    {-0.728, -1.3, 2.55},
    {-1.3, -0.728, 2.55},
    {-1.3, 0.0, 2.55},
    {-0.728, -1.3, 2.4},
    {-1.3, -0.728, 2.4},
    {-1.3, 0.0, 2.4},
    {-0.4, 0.224, 2.55},
    {-0.224, 0.4, 2.55},
    {0.0, 0.4, 2.55},
    {-1.3, 0.728, 2.55},
    {-0.728, 1.3, 2.55},
    {0.0, 1.3, 2.55},
    {-1.3, 0.728, 2.4},
    {-0.728, 1.3, 2.4},
    {0.0, 1.3, 2.4},
    {0.224, 0.4, 2.55},
    {0.4, 0.224, 2.55},
    {0.728, 1.3, 2.55},
    {1.3, 0.728, 2.55},
    {0.728, 1.3, 2.4},
    {1.3, 0.728, 2.4},
    {0.0, 0.0, 0.0},
    {1.5, 0.0, 0.15},
    {1.5, 0.84, 0.15},
    {0.84, 1.5, 0.15},
    {0.0, 1.5, 0.15},
    {1.5, 0.0, 0.075},
    {1.5, 0.84, 0.075},
    {0.84, 1.5, 0.075},
    {0.0, 1.5, 0.075},
    {1.425, 0.0, 0.0},
    {1.425, 0.798, 0.0},
    {0.798, 1.425, 0.0},
    {0.0, 1.425, 0.0},
    {-0.84, 1.5, 0.15},
    {-1.5, 0.84, 0.15},
    {-1.5, 0.0, 0.15},
    {-0.84, 1.5, 0.075},
    {-1.5, 0.84, 0.075},
    {-1.5, 0.0, 0.075},
    {-0.798, 1.425, 0.0},
    {-1.425, 0.798, 0.0},
    {-1.425, 0.0, 0.0},
    {-1.5, -0.84, 0.15},
    {-0.84, -1.5, 0.15},
    {0.0, -1.5, 0.15},
    {-1.5, -0.84, 0.075},
    {-0.84, -1.5, 0.075},
    {0.0, -1.5, 0.075},
    {-1.425, -0.798, 0.0},
    {-0.798, -1.425, 0.0},
    {0.0, -1.425, 0.0},
    {0.84, -1.5, 0.15},
    {1.5, -0.84, 0.15},
    {0.84, -1.5, 0.075},
    {1.5, -0.84, 0.075},
    {0.798, -1.425, 0.0},
    {1.425, -0.798, 0.0},
};

/// The bicubic Bezier patch `p` (Newell's coordinates) at (u, v): u runs along a row of its
/// control points, v across the rows.
Vec3 patch_point(int p, double u, double v) {
  auto bernstein = [](double t) {
    const double s = 1 - t;
    return std::array<double, 4>{s * s * s, 3 * t * s * s, 3 * t * t * s, t * t * t};
  };
  const auto bu = bernstein(u), bv = bernstein(v);
  Vec3 sum{0, 0, 0};
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) {
      const double* c = kPoints[kPatches[p][4 * row + col] - 1];
      sum = sum + (bv[size_t(row)] * bu[size_t(col)]) * Vec3{c[0], c[1], c[2]};
    }
  return sum;
}

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;  // 0-based
};

/// The teapot, `steps` x `steps` quads (two triangles each) per patch. Points the patches share
/// are welded (by position, rounded to 1e-9), so the loader's area-weighted vertex normals are
/// smooth across patch seams; triangles collapsed at the lid's and the bottom's centre are
/// dropped. Newell's patches do not all run the same way round: each is turned so that its
/// normal at its middle points outwards, so the mesh is consistently oriented (main checks).
Mesh teapot(int steps) {
  Mesh mesh;
  std::map<std::array<long long, 3>, int> index_of;
  auto vertex = [&](Vec3 p) {
    const std::array<long long, 3> key = {std::llround(p.x * 1e9), std::llround(p.y * 1e9),
                                          std::llround(p.z * 1e9)};
    const auto [it, added] = index_of.emplace(key, int(mesh.vertices.size()));
    if (added) mesh.vertices.push_back(p);
    return it->second;
  };
  for (int p = 0; p < 32; ++p) {
    // Outward test at the patch's middle.
    const double h = 1e-4;
    const Vec3 c = patch_point(p, 0.5, 0.5);
    const Vec3 n = cross(patch_point(p, 0.5 + h, 0.5) - patch_point(p, 0.5 - h, 0.5),
                         patch_point(p, 0.5, 0.5 + h) - patch_point(p, 0.5, 0.5 - h));
    // Outwards: away from the middle plane for the handle and the spout (12 - 19), from the
    // knob's centre for the lid's knob (20 - 23), from a point inside the pot for the rest.
    const bool handle_or_spout = p >= 12 && p < 20;
    const Vec3 inside = p >= 20 && p < 24 ? Vec3{0, 0, 3.0} : Vec3{0, 0, 1.5};
    const double outward = handle_or_spout ? n.y * c.y : dot(n, c - inside);
    const bool flip = outward < 0;
    std::vector<int> grid;
    for (int j = 0; j <= steps; ++j)
      for (int i = 0; i <= steps; ++i)
        grid.push_back(vertex(patch_point(p, double(i) / steps, double(j) / steps)));
    auto add = [&](int a, int b, int c2) {
      if (a == b || b == c2 || a == c2) return;  // collapsed at a pole
      mesh.triangles.push_back(flip ? std::array<int, 3>{a, c2, b} : std::array<int, 3>{a, b, c2});
    };
    for (int j = 0; j < steps; ++j)
      for (int i = 0; i < steps; ++i) {
        const int a = grid[size_t(j * (steps + 1) + i)];
        const int b = grid[size_t(j * (steps + 1) + i + 1)];
        const int c2 = grid[size_t((j + 1) * (steps + 1) + i + 1)];
        const int d = grid[size_t((j + 1) * (steps + 1) + i)];
        add(a, b, c2);
        add(a, c2, d);
      }
  }
  return mesh;
}

/// Writes `mesh` as OBJ, Newell's z-up coordinates turned to +Y up: (x, y, z) -> (x, z, -y).
void write_teapot_obj(const std::string& path, const Mesh& mesh, int steps) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
  std::fprintf(out,
               "# The Utah teapot (Newell 1975; Crow, IEEE CG&A 7(1), 1987): 32 Bezier patches, "
               "%d x %d quads each, +Y up\n",
               steps, steps);
  for (const Vec3& v : mesh.vertices) std::fprintf(out, "v %.9g %.9g %.9g\n", v.x, v.z, -v.y);
  for (const auto& t : mesh.triangles)
    std::fprintf(out, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
  const bool ok = std::ferror(out) == 0;
  if (std::fclose(out) != 0 || !ok) throw std::runtime_error("cannot write '" + path + "'");
}

/// Counts the edges two triangles run along in the same direction (0 for a consistently
/// oriented mesh).
int same_direction_edges(const Mesh& mesh) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++uses[{t[size_t(k)], t[size_t((k + 1) % 3)]}];
  int clashes = 0;
  for (const auto& [edge, count] : uses) clashes += count - 1;
  return clashes;
}

// ---------------------------------------------------------------------------------------------
// The phantom. Values blend between shapes by their signed distance through the edge response of
// a scanner whose blur is a Gaussian of sigma = 0.8 voxels (a partial volume effect), so surfaces
// are smooth, not terraced, at any zoom. Densities are chosen for the ct preset
// (transfer_function.h): bone and contrast-filled vessels opaque white, soft tissue a faint red;
// the brain is set to -160 HU (a real one is about +30) so that it stays nearly clear and the
// structures inside it show.

constexpr int kVoxels = 160;
constexpr double kBlur = 0.8;  // voxels
constexpr double kReach = 4;   // voxels: beyond this distance a shape's edge response is 0

struct Volume {
  std::vector<float> hu = std::vector<float>(size_t(kVoxels) * kVoxels * kVoxels, -1000.f);
  float& at(int i, int j, int k) {
    return hu[size_t(i) + kVoxels * (size_t(j) + kVoxels * size_t(k))];
  }
};

/// The fraction of a voxel at signed distance d (voxels, negative inside) that a blurred shape
/// covers: 0.5 erfc(d / (sigma sqrt 2)).
double coverage(double d) { return 0.5 * std::erfc(d / (kBlur * std::sqrt(2.0))); }

/// Blends `value` into the voxels of the box [low, high] (clamped to the volume) by
/// coverage(signed_distance(voxel centre)).
template <typename Distance>
void paint(Volume& volume, Vec3 low, Vec3 high, float value, Distance signed_distance) {
  const int i0 = std::max(0, int(std::floor(low.x))),
            i1 = std::min(kVoxels - 1, int(std::ceil(high.x)));
  const int j0 = std::max(0, int(std::floor(low.y))),
            j1 = std::min(kVoxels - 1, int(std::ceil(high.y)));
  const int k0 = std::max(0, int(std::floor(low.z))),
            k1 = std::min(kVoxels - 1, int(std::ceil(high.z)));
  for (int k = k0; k <= k1; ++k)
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double d = signed_distance(Vec3{double(i), double(j), double(k)});
        if (d > kReach) continue;
        const double cover = coverage(d);
        float& v = volume.at(i, j, k);
        v = float((1 - cover) * v + cover * value);
      }
}

/// The signed distance (approximately; exact for a sphere) to the ellipsoid of semi-axes `r`
/// about `c`.
double ellipsoid(Vec3 p, Vec3 c, Vec3 r) {
  const Vec3 q = p - c;
  const Vec3 s{q.x / r.x, q.y / r.y, q.z / r.z};
  return (norm(s) - 1) * std::min({r.x, r.y, r.z});
}

void paint_ellipsoid(Volume& volume, Vec3 c, Vec3 r, float value) {
  const Vec3 pad = r + Vec3{kReach, kReach, kReach};
  paint(volume, c - pad, c + pad, value, [&](Vec3 p) { return ellipsoid(p, c, r); });
}

/// A vessel: a capsule from a to b of radius r.
struct Segment {
  Vec3 a, b;
  double r;
};

/// A random branching tree of vessels from `start` along `direction`, each branch a gently
/// bending run of 4 segments, splitting into two thinner branches until they are thinner than
/// 0.7 voxels or would leave `inside` (the brain).
template <typename Inside>
void grow(std::vector<Segment>& out, std::mt19937& random, Vec3 start, Vec3 direction,
          double length, double radius, int depth, Inside inside) {
  if (radius < 0.7 || depth > 7) return;
  std::normal_distribution<double> bend(0, 0.18);
  Vec3 p = start, d = (1 / norm(direction)) * direction;
  for (int s = 0; s < 4; ++s) {
    d = d + Vec3{bend(random), bend(random), bend(random)};
    d = (1 / norm(d)) * d;
    const Vec3 q = p + (length / 4) * d;
    if (!inside(q)) return;
    out.push_back({p, q, radius});
    p = q;
  }
  // Two children, turned apart about an axis across d.
  std::uniform_real_distribution<double> angle(0, 2 * 3.14159265358979);
  const double a = angle(random);
  Vec3 across = cross(d, std::abs(d.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0});
  across = (1 / norm(across)) * across;
  const Vec3 other = cross(d, across);
  const Vec3 side = std::cos(a) * across + std::sin(a) * other;
  for (double sign : {-1.0, 1.0})
    grow(out, random, p, d + (0.75 * sign) * side, length * 0.8, radius * 0.78, depth + 1, inside);
}

Volume phantom() {
  Volume volume;
  const Vec3 centre{80, 80, 80};
  const Vec3 head{68, 75, 73};  // semi-axes, voxels: left-right, back-front, foot-head
  // Scalp (soft tissue), skull (bone) and brain, as nested ellipsoids.
  paint_ellipsoid(volume, centre, head, 40);
  paint_ellipsoid(volume, centre, head - Vec3{3, 3, 3}, 1100);
  paint_ellipsoid(volume, centre, head - Vec3{9, 9, 9}, -160);
  // The cutaway: the scalp and the skull over the upper front quarter (front = +y, the camera's
  // side at azimuth 0) lifted off, down to the brain.
  paint(volume, {0, centre.y - 12, centre.z - 6}, {kVoxels, kVoxels, kVoxels}, -1000, [&](Vec3 p) {
    const double quarter = std::max(centre.y - 8 - p.y, centre.z - 2 - p.z);
    return std::max(quarter, -ellipsoid(p, centre, head - Vec3{9, 9, 9}));
  });
  // Two ventricles (fluid, 10 HU) and a calcification (700 HU) behind them.
  paint_ellipsoid(volume, centre + Vec3{-11, 2, 6}, {6, 24, 10}, 10);
  paint_ellipsoid(volume, centre + Vec3{11, 2, 6}, {6, 24, 10}, 10);
  paint_ellipsoid(volume, centre + Vec3{0, -26, 8}, {3, 3, 3}, 700);
  // A tumour (110 HU) with a few calcified specks (800 HU) of one to two voxels.
  const Vec3 tumour = centre + Vec3{-28, 26, 24};
  paint_ellipsoid(volume, tumour, {11, 10, 9}, 110);
  const Vec3 specks[] = {{-4, 2, 3}, {3, -3, 2}, {1, 4, -3}, {-2, -4, -2}, {5, 2, -1}, {-1, 0, 5}};
  for (size_t s = 0; s < std::size(specks); ++s) {
    const double r = 0.8 + 0.4 * double(s % 3);  // 0.8, 1.2 or 1.6 voxels
    paint_ellipsoid(volume, tumour + specks[s], {r, r, r}, 800);
  }
  // A tree of contrast-filled vessels (450 HU) rising from the skull base, with an aneurysm on
  // one branch: one distance field (the nearest capsule), painted once.
  const Vec3 brain = head - Vec3{11, 11, 11};
  auto inside = [&](Vec3 p) { return ellipsoid(p, centre, brain) < -2; };
  std::mt19937 random(18);
  std::vector<Segment> vessels;
  grow(vessels, random, centre + Vec3{0, 6, -brain.z + 4}, {0, 0.2, 1}, 22, 3.4, 0, inside);
  std::vector<float> distance(volume.hu.size(), float(kReach + 1));
  auto nearest = [&](Vec3 low, Vec3 high, auto signed_distance) {
    for (int k = std::max(0, int(low.z)); k <= std::min(kVoxels - 1, int(high.z) + 1); ++k)
      for (int j = std::max(0, int(low.y)); j <= std::min(kVoxels - 1, int(high.y) + 1); ++j)
        for (int i = std::max(0, int(low.x)); i <= std::min(kVoxels - 1, int(high.x) + 1); ++i) {
          float& d = distance[size_t(i) + kVoxels * (size_t(j) + kVoxels * size_t(k))];
          d = std::min(d, float(signed_distance(Vec3{double(i), double(j), double(k)})));
        }
  };
  for (const Segment& s : vessels) {
    const Vec3 pad{s.r + kReach, s.r + kReach, s.r + kReach};
    const Vec3 low{std::min(s.a.x, s.b.x), std::min(s.a.y, s.b.y), std::min(s.a.z, s.b.z)};
    const Vec3 high{std::max(s.a.x, s.b.x), std::max(s.a.y, s.b.y), std::max(s.a.z, s.b.z)};
    const Vec3 ab = s.b - s.a;
    nearest(low - pad, high + pad, [&](Vec3 p) {
      const double t = std::clamp(dot(p - s.a, ab) / dot(ab, ab), 0.0, 1.0);
      return norm(p - (s.a + t * ab)) - s.r;
    });
  }
  const Vec3 sac = vessels[vessels.size() / 3].b + Vec3{2.5, 2.5, 1};
  const Vec3 pad{4 + kReach, 4 + kReach, 4 + kReach};
  nearest(sac - pad, sac + pad, [&](Vec3 p) { return norm(p - sac) - 4; });
  paint(volume, {0, 0, 0}, {kVoxels, kVoxels, kVoxels}, 450, [&](Vec3 p) {
    return distance[size_t(p.x) + kVoxels * (size_t(p.y) + kVoxels * size_t(p.z))];
  });
  return volume;
}

/// Writes `volume` as a NRRD file: a text header, then the int16 values (little endian) as one
/// gzip stream.
void write_phantom_nrrd(const std::string& path, const Volume& volume) {
  std::vector<unsigned char> raw;
  raw.reserve(volume.hu.size() * 2);
  for (float value : volume.hu) {
    const auto v = uint16_t(int16_t(std::lround(std::clamp(value, -1024.f, 3071.f))));
    raw.push_back(uint8_t(v & 0xff));
    raw.push_back(uint8_t(v >> 8));
  }
  z_stream stream{};
  if (deflateInit2(&stream, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("zlib: deflateInit2 failed");
  std::vector<unsigned char> packed(deflateBound(&stream, uLong(raw.size())));
  stream.next_in = raw.data();
  stream.avail_in = uInt(raw.size());
  stream.next_out = packed.data();
  stream.avail_out = uInt(packed.size());
  const int status = deflate(&stream, Z_FINISH);
  packed.resize(stream.total_out);
  deflateEnd(&stream);
  if (status != Z_STREAM_END) throw std::runtime_error("zlib: deflate did not finish");
  std::ofstream out(path, std::ios::binary);
  out << "NRRD0004\n"
      << "# make_scene_examples: a CT-like head phantom, Hounsfield-like units\n"
      << "type: int16\ndimension: 3\nsizes: " << kVoxels << ' ' << kVoxels << ' ' << kVoxels
      << "\nspacings: 1 1 1\nendian: little\nencoding: gzip\n\n";
  out.write(reinterpret_cast<const char*>(packed.data()), std::streamsize(packed.size()));
  if (!out.flush()) throw std::runtime_error("cannot write '" + path + "'");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: make_scene_examples OUTPUT_FOLDER [STEPS]\n");
    return 2;
  }
  const int steps = argc == 3 ? std::atoi(argv[2]) : 33;
  if (steps < 1 || steps > 200) {
    std::fprintf(stderr, "make_scene_examples: STEPS must be in [1, 200], got '%s'\n", argv[2]);
    return 2;
  }
  const std::filesystem::path folder = argv[1];
  try {
    std::filesystem::create_directories(folder);
    const Mesh pot = teapot(steps);
    const int clashes = same_direction_edges(pot);
    if (clashes != 0)
      throw std::runtime_error("the teapot's patches are not consistently oriented (" +
                               std::to_string(clashes) + " edges)");
    const std::string obj = (folder / "teapot.obj").string();
    write_teapot_obj(obj, pot, steps);
    const geolens::TriangleMesh read = geolens::load_obj(obj);
    std::printf("make_scene_examples: wrote %s: %lld vertices, %lld triangles\n", obj.c_str(),
                (long long)read.V.rows(), (long long)read.F.rows());

    const std::string nrrd = (folder / "phantom.nrrd").string();
    write_phantom_nrrd(nrrd, phantom());
    const geolens::ScalarVolume volume = geolens::load_nrrd(nrrd);
    const auto [low, high] = std::minmax_element(volume.values.begin(), volume.values.end());
    std::printf("make_scene_examples: wrote %s: %d x %d x %d voxels, %.0f to %.0f HU, %.1f MB\n",
                nrrd.c_str(), volume.nx, volume.ny, volume.nz, double(*low), double(*high),
                double(std::filesystem::file_size(nrrd)) / 1e6);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_scene_examples: %s\n", e.what());
    return 1;
  }
  return 0;
}
