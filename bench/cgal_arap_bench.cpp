// CGAL's ARAP parameterizer (CGAL::Surface_mesh_parameterization::ARAP_parameterizer_3, after
// Liu et al. 2008) against geolens's flattening of the same lifted mesh (issue 5), with the ARAP
// energy of both results measured by one function. Built only where CGAL is installed
// (bench/CMakeLists.txt): CGAL is a benchmark-only dependency.

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/ARAP_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <benchmark/benchmark.h>

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "geolens/geometry/grid.h"
#include "lens/flatten.h"
#include "lens/lift.h"

namespace geolens {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMP = CGAL::Surface_mesh_parameterization;

// bench/lens_bench.cpp's scene: a 1024 px image, one gaussian lens r = 150 px at the centre with
// the height the calibration finds for zoom 2 (h0 = 0.76 r).
struct Scene {
  explicit Scene(int mesh) : grid(make_grid(1024, 1024, mesh)) {
    lifted = lift(grid.V, {lens}, {0.76 * 150});
  }
  Grid grid;
  Lens lens{Region::circle({512, 512}, 150)};
  Lifted lifted;
};

/// The ARAP energy of a flattening and what a uniform scale of it can reach.
struct ArapEnergy {
  double energy = 0;  ///< E(X), pixels^2
  double scaled = 0;  ///< min over s > 0 of E(s X), pixels^2
  double scale = 0;   ///< the s reaching it
  int flipped = 0;    ///< triangles whose image has det J <= 0
};

/// E(X) = sum_t A_t ||J_t - R_t||_F^2 over the triangles F (#F x 3) of the lifted mesh V3
/// (#V x 3, pixels) and their images in X (#V x 2): A_t the 3D area, J_t the Jacobian from the
/// triangle's isometric planar copy to its image, R_t the rotation closest to J_t. The same
/// function measures every method's result.
ArapEnergy arap_energy(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                       const Eigen::MatrixX2d& X) {
  // With m_t = max over rotations R of tr(R^T J_t) = |(J00 + J11, J10 - J01)|,
  // ||s J_t - R_t||^2 = s^2 ||J_t||^2 - 2 s m_t + 2 (R_t does not depend on s > 0), so
  // E(s X) = s^2 sum A_t ||J_t||^2 - 2 s sum A_t m_t + 2 sum A_t.
  double area = 0, stretch = 0, alignment = 0;
  ArapEnergy e;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d e1 = V3.row(F(f, 1)) - V3.row(F(f, 0));
    const Eigen::Vector3d e2 = V3.row(F(f, 2)) - V3.row(F(f, 0));
    const double l1 = e1.norm(), cross = e1.cross(e2).norm();
    Eigen::Matrix2d planar, image;
    planar << l1, e1.dot(e2) / l1, 0, cross / l1;
    image.col(0) = (X.row(F(f, 1)) - X.row(F(f, 0))).transpose();
    image.col(1) = (X.row(F(f, 2)) - X.row(F(f, 0))).transpose();
    const Eigen::Matrix2d J = image * planar.inverse();
    const double a = 0.5 * cross;
    area += a;
    stretch += a * J.squaredNorm();
    alignment += a * std::hypot(J(0, 0) + J(1, 1), J(1, 0) - J(0, 1));
    if (J.determinant() <= 0) ++e.flipped;
  }
  e.energy = stretch - 2 * alignment + 2 * area;
  e.scale = alignment / stretch;
  e.scaled = 2 * area - alignment * alignment / stretch;
  return e;
}

void report(benchmark::State& state, const Eigen::MatrixX2d& X, const Scene& s) {
  const ArapEnergy e = arap_energy(s.lifted.V, s.grid.F, X);
  state.counters["vertices"] = double(X.rows());
  state.counters["energy"] = e.energy;
  state.counters["energy_scaled"] = e.scaled;
  state.counters["best_scale"] = e.scale;
  state.counters["flipped"] = e.flipped;
}

SurfaceMesh to_surface_mesh(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F) {
  SurfaceMesh mesh;
  std::vector<SurfaceMesh::Vertex_index> v(size_t(V3.rows()));
  for (Eigen::Index i = 0; i < V3.rows(); ++i)
    v[size_t(i)] = mesh.add_vertex(Kernel::Point_3(V3(i, 0), V3(i, 1), V3(i, 2)));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (mesh.add_face(v[size_t(F(f, 0))], v[size_t(F(f, 1))], v[size_t(F(f, 2))]) ==
        SurfaceMesh::null_face())
      throw std::runtime_error("to_surface_mesh: face " + std::to_string(f) + " is not manifold");
  }
  return mesh;
}

// CGAL's parameterize() with ARAP_parameterizer_3's defaults but lambda (an MVC initial map on a
// circle, up to 50 iterations, stop at a relative energy change < 1e-6, SparseLU), from the
// surface mesh to its uv map. Args: mesh, k for lambda = 10^k. CGAL's lambda weighs
// (a^2 + b^2 - 1)^2 against the fit of each triangle's similarity [a b; -b a]; ARAP is the limit
// of a large lambda, and CGAL takes its exact ARAP branch once the fit's coefficients are below
// 1e-10 lambda, which 10^20 ensures for pixel-sized triangles. 10^3 is CGAL's default. lambda = 0
// would be ASAP (LSCM) with two pinned vertices, not ARAP; on these grids (CGAL 5.5) its result
// flips triangles and the post-processor then fails to solve.
void BM_CgalArap(benchmark::State& state) {
  const Scene s(int(state.range(0)));
  const double lambda = std::pow(10.0, double(state.range(1)));
  SurfaceMesh mesh = to_surface_mesh(s.lifted.V, s.grid.F);
  const auto border = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
  auto uv = mesh.add_property_map<SurfaceMesh::Vertex_index, Kernel::Point_2>("v:uv").first;
  for (auto _ : state) {
    const SMP::Error_code status =
        SMP::parameterize(mesh, SMP::ARAP_parameterizer_3<SurfaceMesh>(lambda), border, uv);
    if (status != SMP::OK) {
      state.SkipWithError(SMP::get_error_message(status));
      return;
    }
  }
  Eigen::MatrixX2d X(s.lifted.V.rows(), 2);
  for (const SurfaceMesh::Vertex_index v : mesh.vertices()) {
    X(Eigen::Index(v.idx()), 0) = uv[v].x();
    X(Eigen::Index(v.idx()), 1) = uv[v].y();
  }
  report(state, X, s);
}

// geolens's plain ARAP flattening (cotan weights, the paper's metric with alpha 0, free
// boundary) from the projection of the lifted mesh, factorization included. Args: mesh, k for
// the stop at a relative energy change <= 10^-k (3: the paper's 0.1 %; 6: CGAL's default stop).
void BM_GeolensArap(benchmark::State& state) {
  const Scene s(int(state.range(0)));
  FlattenOptions o;
  o.weights = FlattenWeights::kCotan;
  o.metric = Metric::kPaper;
  o.alpha = 0;
  o.boundary = Boundary::kFree;
  o.tolerance = std::pow(10.0, -double(state.range(1)));
  FlattenResult r;
  for (auto _ : state) r = flatten(s.lifted.V, s.grid.F, s.lifted.level, s.grid.sides, o);
  report(state, r.X, s);
  state.counters["flatten_iterations"] = r.iterations;
  state.counters["converged"] = r.converged;
}

// CGAL takes seconds per run: one iteration per repetition.
BENCHMARK(BM_CgalArap)
    ->ArgsProduct({{100, 200}, {3, 20}})
    ->ArgNames({"mesh", "lambda_exp"})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GeolensArap)
    ->ArgsProduct({{100, 200}, {3, 4, 6}})
    ->ArgNames({"mesh", "tol_exp"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace geolens
