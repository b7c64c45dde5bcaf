#include "geolens/lens/lens_session.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/eval/comparison.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens_method.h"
#include "geolens/lens/lens_worker.h"
#include "geolens/measure/distortion.h"
#include "geolens/warp/warp_map.h"
#include "support/lens_options.h"

namespace geolens {
namespace {

// The interactive path against the exact, stateless one: a lens dragged in 4 px steps. Every
// update keeps its zoom, flips nothing, and its energy is within 1 % of a fresh exact solve of
// the same lens (same heights, same grid: subdivision off for the comparison); for a circle (the
// lift model) and a star polygon (the field model).
TEST(LensSession, UpdateMatchesTheExactSolveWhileTheLensMoves) {
  LensOptions options = test::auto_model();
  options.mesh = 60;
  options.subdivision.max_levels = 0;
  auto star = [](const Eigen::Vector2d& centre) {
    std::vector<Eigen::Vector2d> p;
    for (int k = 0; k < 10; ++k) {
      const double r = k % 2 == 0 ? 100 : 45, a = M_PI / 2 + k * M_PI / 5;
      p.push_back(centre + r * Eigen::Vector2d(std::cos(a), -std::sin(a)));
    }
    return Region::polygon(p);
  };
  for (const bool polygon : {false, true}) {
    LensSession moving(600, 500, options);
    const GeometricLens exact(600, 500, options);
    for (int step = 0; step < 6; ++step) {
      const Eigen::Vector2d centre(250.0 + 4 * step, 240.0 - 3 * step);
      const Lens lens{polygon ? star(centre) : Region::circle(centre, 90), 2.5};
      const LensResult r = moving.update({lens});
      SCOPED_TRACE(std::string(polygon ? "star" : "circle") + ", step " + std::to_string(step));
      EXPECT_EQ(r.model, polygon ? LensModel::kField : LensModel::kLift);
      EXPECT_NEAR(r.zoom_measured[0] / 2.5, 1.0, 0.03);
      EXPECT_EQ(summarize(measure_triangles(r.warp)).flipped, 0);
      EXPECT_TRUE(r.flattening.converged);
      if (step > 0) EXPECT_LE(r.solves, 2) << "the previous heights should be reused";
      const LensResult reference = exact.solve_with_heights({lens}, r.lift_heights_px);
      EXPECT_NEAR(r.flattening.energy.back() / reference.flattening.energy.back(), 1.0, 0.01);
    }
  }
}

// The interactive path under an erratic user: small moves, jumps, stops, zoom changes, a second
// lens coming and going, a polygon switching the model. Every frame keeps its zoom, folds
// nothing and ends within 1 % of a fresh exact solve's energy at the same heights.
TEST(LensSession, UpdateSurvivesAnErraticSequence) {
  LensOptions options = test::auto_model();
  options.mesh = 50;
  LensSession moving(800, 600, options);
  const GeometricLens exact(800, 600, options);
  const std::vector<Eigen::Vector2d> square = {{500, 150}, {620, 150}, {620, 260}, {500, 260}};
  std::vector<Lens> lenses = {Lens{Region::circle({300, 300}, 90), 2.0}};
  for (int frame = 0; frame < 24; ++frame) {
    Lens& first = lenses[0];
    const Eigen::Vector2d c = first.region.peak();
    switch (frame % 8) {
      case 0:
      case 1:
      case 2:  // small moves
        first.region = Region::circle(c + Eigen::Vector2d(5, -3), 90);
        break;
      case 3:  // a stop: the same lenses again
        break;
      case 4:  // a jump
        first.region = Region::circle({800 - c.x(), 600 - c.y()}, 90);
        break;
      case 5:  // a new zoom, and a second lens (a polygon: the field model)
        first.zoom = first.zoom == 2.0 ? 2.5 : 2.0;
        lenses.push_back(Lens{Region::polygon(square), 2.0});
        break;
      case 6:  // the polygon moves with the circle
        first.region = Region::circle(c + Eigen::Vector2d(-4, 4), 90);
        break;
      case 7:  // the polygon goes
        lenses.pop_back();
        break;
    }
    SCOPED_TRACE("frame " + std::to_string(frame));
    const LensResult r = moving.update(lenses);
    for (size_t k = 0; k < lenses.size(); ++k)
      EXPECT_NEAR(r.zoom_measured[k] / lenses[k].zoom, 1.0, 0.1) << "lens " << k;
    EXPECT_EQ(summarize(measure_triangles(r.warp)).flipped, 0);
    const LensResult reference = exact.solve_with_heights(lenses, r.lift_heights_px);
    EXPECT_EQ(r.model, reference.model);
    EXPECT_NEAR(r.flattening.energy.back() / reference.flattening.energy.back(), 1.0, 0.01);
  }
}

// The largest distance between two warps' screen positions (same mesh), pixels.
double screen_gap(const Magnification& a, const Magnification& b) {
  EXPECT_EQ(a.warp.screen.rows(), b.warp.screen.rows());
  if (a.warp.screen.rows() != b.warp.screen.rows()) return INFINITY;
  return (a.warp.screen - b.warp.screen).rowwise().norm().maxCoeff();
}

Lens focus_circle(double x, double y) { return Lens{Region::circle({x, y}, 100), 2.0}; }

// Progress reports every step of the flattening with its energy: for a focus lens (one solve)
// the reports are exactly the result's energy sequence, numbered as solve 1.
TEST(LensSession, ProgressReportsEveryStepOfTheSolve) {
  LensSession session(1024, 1024);
  std::vector<SolveProgress> reports;
  SolveControl control;
  control.progress = [&](const SolveProgress& p) { reports.push_back(p); };
  const LensResult r = session.update({focus_circle(500, 480)}, control);
  ASSERT_EQ(r.solves, 1);
  ASSERT_EQ(reports.size(), r.flattening.energy.size());
  for (size_t i = 0; i < reports.size(); ++i) {
    EXPECT_EQ(reports[i].solve, 1);
    EXPECT_EQ(reports[i].iteration, int(i));
    EXPECT_EQ(reports[i].energy, r.flattening.energy[i]);
  }
}

// The lift model calibrates over several solves: each is reported from its first step, in
// order, and as many as the result counts.
TEST(LensSession, ProgressNumbersTheCalibrationSolves) {
  LensOptions options = test::auto_model();
  options.mesh = 60;
  LensSession session(800, 600, options);
  std::vector<SolveProgress> reports;
  SolveControl control;
  control.progress = [&](const SolveProgress& p) { reports.push_back(p); };
  const LensResult r = session.update({Lens{Region::circle({400, 300}, 120), 3.0}}, control);
  ASSERT_FALSE(reports.empty());
  int solve = 0;
  for (size_t i = 0; i < reports.size(); ++i) {
    if (reports[i].iteration == 0) {
      EXPECT_EQ(reports[i].solve, ++solve);
    } else {
      EXPECT_EQ(reports[i].solve, solve);
      EXPECT_EQ(reports[i].iteration, reports[i - 1].iteration + 1);
    }
  }
  EXPECT_EQ(solve, r.solves);
}

// A cancelled update throws and leaves the session usable: the next update of the same lens is
// the fresh session's answer (a focus lens starts from its power-law start whatever came before).
TEST(LensSession, ACancelledUpdateThrowsAndTheNextIsExact) {
  LensSession session(1024, 1024);
  session.update({focus_circle(500, 480)});
  std::atomic<bool> cancel{false};
  SolveControl control{&cancel, [&](const SolveProgress&) { cancel = true; }};
  EXPECT_THROW(session.update({focus_circle(530, 470)}, control), Cancelled);
  const LensResult again = session.update({focus_circle(530, 470)});
  const LensResult fresh = LensSession(1024, 1024).update({focus_circle(530, 470)});
  EXPECT_LT(screen_gap(again, fresh), 1e-6);
  EXPECT_EQ(again.flattening.iterations, fresh.flattening.iterations);
}

// Cancelled in the middle of a calibration (lift model), the session's next update still
// reaches its zoom without a fold.
TEST(LensSession, ACancelledCalibrationLeavesTheSessionUsable) {
  LensOptions options = test::auto_model();
  options.mesh = 60;
  LensSession session(800, 600, options);
  session.update({Lens{Region::circle({400, 300}, 120), 2.0}});
  std::atomic<bool> cancel{false};
  SolveControl control{&cancel, [&](const SolveProgress& p) {
                         if (p.solve == 2) cancel = true;
                       }};
  const Lens moved{Region::circle({430, 280}, 120), 3.0};  // a new zoom: calibration again
  EXPECT_THROW(session.update({moved}, control), Cancelled);
  const LensResult r = session.update({moved});
  EXPECT_NEAR(r.zoom_measured[0] / 3.0, 1.0, options.zoom_tolerance + 1e-9);
  EXPECT_EQ(summarize(measure_triangles(r.warp)).flipped, 0);
}

// An invalid lens is refused before anything changes: the same valid lens again gives the same
// frame as before.
TEST(LensSession, AnInvalidLensLeavesTheSessionAsItWas) {
  LensSession session(1024, 1024);
  const LensResult first = session.update({focus_circle(500, 480)});
  EXPECT_THROW(session.update({Lens{Region::circle({500, 480}, 100), 9.0}}), InvalidInput);
  EXPECT_THROW(session.update({Lens{Region::circle({2000, 480}, 100), 2.0}}), InvalidInput);
  const LensResult again = session.update({focus_circle(500, 480)});
  EXPECT_LT(screen_gap(first, again), 1e-6);
}

// A star polygon, radius 120 px, about `centre`.
Lens focus_star(const Eigen::Vector2d& centre, double zoom = 2) {
  std::vector<Eigen::Vector2d> p;
  for (int k = 0; k < 10; ++k) {
    const double r = k % 2 == 0 ? 120 : 46, a = M_PI / 2 + k * M_PI / 5;
    p.push_back(centre + r * Eigen::Vector2d(std::cos(a), -std::sin(a)));
  }
  return Lens{Region::polygon(p), zoom};
}

// The largest distance between where two warps send the points of an 8 px lattice, pixels.
double picture_gap(const Magnification& a, const Magnification& b, double width, double height) {
  const WarpMap map_a(a.warp), map_b(b.warp);
  double worst = 0;
  for (double y = 4; y < height; y += 8) {
    for (double x = 4; x < width; x += 8) {
      const std::optional<Eigen::Vector2d> pa = map_a.forward({x, y}), pb = map_b.forward({x, y});
      if (!pa || !pb) return INFINITY;
      worst = std::max(worst, (*pa - *pb).norm());
    }
  }
  return worst;
}

// A draft is solved on the mesh that follows the region and the footprint, not refined where the
// ring bends: fewer triangles, the same exact focus, a picture within a few pixels of the full
// frame's. Drafts and full frames keep their caches apart: a draft after a full frame is the
// draft before it.
TEST(LensSession, ADraftIsTheFullFrameOnAnUnrefinedMesh) {
  LensSession session(1024, 1024);
  const std::vector<Lens> lenses = {focus_star({512, 512})};
  const LensResult draft = session.update(lenses, {}, true);
  const LensResult full = session.update(lenses);
  EXPECT_TRUE(draft.draft);
  EXPECT_FALSE(full.draft);
  EXPECT_LT(draft.mesh.F.rows(), full.mesh.F.rows());
  for (const LensResult* r : {&draft, &full}) {
    const TriangleDistortion measures = measure_triangles(r->warp);
    EXPECT_EQ(summarize(measures).flipped, 0);
    const FocusMeasure focus = measure_foci(r->warp, measures, lenses).front();
    EXPECT_NEAR(focus.zoom, 2, 0.01);
    EXPECT_LT(focus.uniformity, 1.01);
  }
  const double gap = picture_gap(draft, full, 1024, 1024);
  EXPECT_GT(gap, 0);
  EXPECT_LT(gap, 3);
  EXPECT_LT(screen_gap(draft, session.update(lenses, {}, true)), 1e-9);
}

// LensOptions::draft_mesh: drafts on their own, coarser grid (about a quarter of the triangles
// at half the vertices), as sound as a full frame; the full frames are those of a session
// without it.
TEST(LensSession, DraftsOnTheirOwnGrid) {
  LensOptions options;
  options.draft_mesh = 50;
  LensSession session(1024, 1024, options);
  LensSession plain(1024, 1024);
  const std::vector<Lens> lenses = {focus_circle(500, 480)};
  const LensResult draft = session.update(lenses, {}, true);
  const LensResult plain_draft = plain.update(lenses, {}, true);
  EXPECT_TRUE(draft.draft);
  EXPECT_LT(draft.mesh.F.rows(), plain_draft.mesh.F.rows() / 3);
  const TriangleDistortion measures = measure_triangles(draft.warp);
  EXPECT_EQ(summarize(measures).flipped, 0);
  const FocusMeasure focus = measure_foci(draft.warp, measures, lenses).front();
  EXPECT_NEAR(focus.zoom, 2, 0.01);
  EXPECT_LT(focus.uniformity, 1.01);
  const LensResult full = session.update(lenses);
  EXPECT_FALSE(full.draft);
  EXPECT_LT(screen_gap(full, plain.update(lenses)), 1e-9);
  options.draft_mesh = 3;
  EXPECT_THROW(LensSession(1024, 1024, options), InvalidInput);
}

// A draft its grid cannot hold (a circle under two cells of the 24 grid beside a large lens:
// GeometricLens says mesh_limited) is solved on the next draft grid, twice as fine: still a
// draft, the one a session drafting on the 48 grid makes, coarser than the full frame. (A circle
// r 90 2 px off a side was held by the 24 grid until it was magnified about the side's point.)
TEST(LensSession, ADraftItsGridCannotHoldGoesToAFinerDraftGrid) {
  LensOptions options;
  options.mesh = 24;
  const std::vector<Lens> lenses = {Lens{Region::circle({300, 300}, 200), 2},
                                    Lens{Region::circle({850, 850}, 20), 3}};
  ASSERT_TRUE(GeometricLens(1024, 1024, options).solve(lenses).mesh_limited);
  options.mesh = 100;
  options.draft_mesh = 24;
  LensSession session(1024, 1024, options);
  options.draft_mesh = 48;
  LensSession finer(1024, 1024, options);
  const LensResult draft = session.update(lenses, {}, true);
  const LensResult expected = finer.update(lenses, {}, true);
  EXPECT_TRUE(draft.draft);
  EXPECT_TRUE(expected.draft);
  ASSERT_EQ(draft.mesh.F.rows(), expected.mesh.F.rows());
  EXPECT_LT(screen_gap(draft, expected), 1e-9);
  EXPECT_LT(draft.mesh.F.rows(), session.update(lenses).mesh.F.rows() / 2);
}

// A lens moved clear of the image border is solved on its last mesh, moved with it: the same
// triangles, every vertex shifted by the move; and the picture is a fresh solve's, on its own
// mesh, within a tenth of a pixel (0.055 px measured; the 4x-finer criterion is 0.5 px).
TEST(LensSession, ALensMovedClearOfTheBorderKeepsItsMesh) {
  LensSession session(2048, 2048);
  const Eigen::Vector2d shift(7.25, -3.5);
  const LensResult before = session.update({focus_star({1000, 1020})});
  const Lens moved = focus_star(Eigen::Vector2d(1000, 1020) + shift);
  const LensResult after = session.update({moved});
  ASSERT_EQ(after.mesh.F.rows(), before.mesh.F.rows());
  EXPECT_TRUE(after.mesh.F == before.mesh.F);
  Eigen::MatrixX2d expected = before.mesh.V;
  expected.rowwise() += shift.transpose();
  EXPECT_LT((after.mesh.V - expected).rowwise().norm().maxCoeff(), 1e-9);
  EXPECT_LT(picture_gap(after, GeometricLens(2048, 2048).solve({moved}), 2048, 2048), 0.1);
}

// The UI thread submits a lens dragged across the image as fast as it can and reads the latest
// frame meanwhile: the frames it sees only move forward, and once the worker is idle the last
// request is the one shown, equal to a fresh solve of its lens.
TEST(LensWorker, TheLatestRequestIsSolvedWhileTheCallerReads) {
  LensWorker worker{LensSession(1024, 1024)};
  std::uint64_t seen = 0, last = 0;
  for (int step = 0; step < 15; ++step) {
    last = worker.submit({focus_circle(400.0 + 10 * step, 500)});
    const LensFrame frame = worker.latest();
    EXPECT_GE(frame.request, seen);
    seen = frame.request;
    EXPECT_EQ(frame.result == nullptr, frame.request == 0);
  }
  worker.wait_idle();
  const LensFrame frame = worker.latest();
  EXPECT_EQ(frame.request, last);
  ASSERT_NE(frame.result, nullptr);
  EXPECT_TRUE(frame.error.empty());
  const LensResult fresh = GeometricLens(1024, 1024).solve({focus_circle(540, 500)});
  EXPECT_LT(screen_gap(*frame.result, fresh), 1e-6);
}

// A session's worker shows drafts while requests come and the full frame once they stop: the
// frame it shows at rest is not a draft, and is a fresh solve's.
TEST(LensWorker, ShowsTheFullFrameOnceTheRequestsStop) {
  LensWorker worker{LensSession(1024, 1024)};
  for (int step = 0; step < 8; ++step) worker.submit({focus_star({440.0 + 8 * step, 500})});
  worker.wait_idle();
  const LensFrame frame = worker.latest();
  ASSERT_NE(frame.result, nullptr);
  EXPECT_FALSE(frame.result->draft);
  const LensResult fresh = GeometricLens(1024, 1024).solve({focus_star({496, 500})});
  EXPECT_LT(picture_gap(*frame.result, fresh, 1024, 1024), 1e-6);
}

// A draft waits `settle` for the next request before its full frame is solved: a request
// within it is drafted without the full frame of the one before, and cancel() while a draft
// settles keeps the draft (a settle of a minute, so neither depends on the machine's speed).
TEST(LensWorker, ADraftSettlesBeforeItsFullFrame) {
  LensWorker worker{LensSession(1024, 1024), nullptr, std::chrono::minutes(1)};
  auto shown = [&](std::uint64_t request) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    LensFrame frame = worker.latest();
    for (; frame.request != request && std::chrono::steady_clock::now() < deadline;
         frame = worker.latest())
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    EXPECT_EQ(frame.request, request);
    return frame;
  };
  worker.submit({focus_star({440, 500})});
  const LensFrame first = shown(1);
  ASSERT_NE(first.result, nullptr);
  EXPECT_TRUE(first.result->draft);
  worker.submit({focus_star({450, 500})});
  const LensFrame second = shown(2);  // not the full frame of request 1 first
  ASSERT_NE(second.result, nullptr);
  EXPECT_TRUE(second.result->draft);
  // Without the settle the full frame would be shown by now (about 40 ms).
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_TRUE(worker.latest().result->draft);
  const auto start = std::chrono::steady_clock::now();
  worker.cancel();
  worker.wait_idle();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  const LensFrame frame = worker.latest();
  EXPECT_EQ(frame.request, 2u);
  ASSERT_NE(frame.result, nullptr);
  EXPECT_TRUE(frame.result->draft);
}

// wait_for: a caller that waits for its request after submitting sees it answered (a draft
// first), and a cancelled request is not waited for.
TEST(LensWorker, WaitForReturnsOnceTheRequestIsAnswered) {
  LensWorker worker{LensSession(1024, 1024)};
  const std::uint64_t request = worker.submit({focus_circle(500, 480)});
  EXPECT_TRUE(worker.wait_for(request, std::chrono::minutes(1)));
  EXPECT_EQ(worker.latest().request, request);
  ASSERT_NE(worker.latest().result, nullptr);
  worker.wait_idle();
  const std::uint64_t dropped = worker.submit({focus_circle(520, 480)});
  worker.cancel();
  const auto start = std::chrono::steady_clock::now();
  worker.wait_for(dropped, std::chrono::minutes(1));
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  EXPECT_FALSE(worker.wait_for(dropped + 1, std::chrono::milliseconds(0)));
}

// cancel() stops the solve under way: its request is dropped and the frame before stays.
TEST(LensWorker, CancelDropsTheSolveUnderWay) {
  LensOptions options = test::auto_model();
  options.mesh = 150;  // a calibrated lift: long enough to be caught running
  std::atomic<bool> armed{false}, running{false};
  LensWorker worker{LensSession(1024, 1024, options), [&](const SolveProgress&) {
                      if (armed) running = true;
                    }};
  worker.submit({Lens{Region::circle({500, 500}, 150), 2.0}});
  worker.wait_idle();
  ASSERT_EQ(worker.latest().request, 1u);
  armed = true;
  worker.submit({Lens{Region::circle({520, 500}, 150), 3.5}});
  while (!running) std::this_thread::yield();
  worker.cancel();
  worker.wait_idle();
  const LensFrame frame = worker.latest();
  EXPECT_EQ(frame.request, 1u);
  EXPECT_EQ(frame.failed_request, 0u);
  EXPECT_EQ(worker.submit({Lens{Region::circle({520, 500}, 150), 2.0}}), 3u);
  worker.wait_idle();
  EXPECT_EQ(worker.latest().request, 3u);
}

// Any lens method runs on a worker: a classic lens answers the latest request as a direct call
// would, and a request cancelled while its (unstoppable) solve runs is dropped.
TEST(LensWorker, RunsAClassicLensAndDropsACancelledAnswer) {
  auto fisheye = std::make_shared<const ClassicMethod>(ClassicLens::kFisheye);
  std::atomic<bool> armed{false}, running{false};
  LensWorker worker{method_job(fisheye, 1024, 1024), nullptr};
  worker.submit({focus_circle(500, 480)});
  worker.wait_idle();
  LensFrame frame = worker.latest();
  ASSERT_NE(frame.result, nullptr);
  EXPECT_GT(frame.solve_ms, 0);
  EXPECT_LT(screen_gap(*frame.result, fisheye->magnify({focus_circle(500, 480)}, 1024, 1024)),
            1e-9);
  // Cancel a request while it runs: a job that sleeps until told, on the same contract.
  LensWorker slow{
      [&](const std::vector<Lens>& lenses, const SolveControl&) {
        running = true;
        while (!armed) std::this_thread::yield();
        return std::shared_ptr<const Magnification>(
            std::make_shared<const Magnification>(fisheye->magnify(lenses, 1024, 1024)));
      },
      nullptr};
  slow.submit({focus_circle(500, 480)});
  while (!running) std::this_thread::yield();
  slow.cancel();
  armed = true;
  slow.wait_idle();
  EXPECT_EQ(slow.latest().request, 0u);
  EXPECT_EQ(slow.latest().result, nullptr);
  EXPECT_THROW(LensWorker(LensJob(), nullptr), InvalidInput);
  EXPECT_THROW(method_job(nullptr, 10, 10), InvalidInput);
}

// A request that fails keeps the last result on show and says why; the next success clears it.
TEST(LensWorker, AFailedRequestKeepsTheLastResultAndSaysWhy) {
  LensWorker worker{LensSession(1024, 1024)};
  worker.submit({focus_circle(500, 480)});
  worker.wait_idle();
  worker.submit({Lens{Region::circle({500, 480}, 100), 9.0}});
  worker.wait_idle();
  LensFrame frame = worker.latest();
  EXPECT_EQ(frame.request, 1u);
  ASSERT_NE(frame.result, nullptr);
  EXPECT_EQ(frame.failed_request, 2u);
  EXPECT_NE(frame.error.find("zoom"), std::string::npos) << frame.error;
  worker.submit({focus_circle(510, 480)});
  worker.wait_idle();
  frame = worker.latest();
  EXPECT_EQ(frame.request, 3u);
  EXPECT_EQ(frame.failed_request, 0u);
  EXPECT_TRUE(frame.error.empty());
}

}  // namespace
}  // namespace geolens
