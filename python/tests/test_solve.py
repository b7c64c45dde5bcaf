"""GeometricLens: zooms, flips, the warp's arrays and maps, stats, the CLI's figures, threads."""

import threading
import time

import geolens
import numpy as np
import pytest

L_POLYGON = np.array([[200, 220], [260, 220], [260, 360], [400, 360], [400, 420],
                      [200, 420]])


@pytest.fixture(scope="module")
def solved():
    """A zoom-2 circle on the demo image's size, solved with the default options."""
    return geolens.GeometricLens(1024, 1024).solve(geolens.circle(500, 500, 100, zoom=2))


@pytest.mark.parametrize("zoom", [1.5, 2, 3])
def test_circle_reaches_its_zoom_without_flips(zoom, flips):
    result = geolens.GeometricLens(1024, 1024).solve([geolens.circle(500, 500, 80, zoom=zoom)])
    assert result.zoom_measured[0] == pytest.approx(zoom, rel=0.1)
    assert result.stats["flipped"] == 0
    assert flips(result.warp) == 0


def test_polygon_reaches_its_zoom_without_flips(flips):
    result = geolens.GeometricLens(1024, 1024).solve(geolens.polygon(L_POLYGON, zoom=1.6))
    assert result.zoom_measured[0] == pytest.approx(1.6, rel=0.1)
    assert result.stats["lenses"][0]["focus"]["uniformity"] == pytest.approx(1, abs=1e-6)
    assert flips(result.warp) == 0


def test_lens_that_does_not_fit_is_solved_at_the_zoom_that_fits():
    result = geolens.GeometricLens(1024, 1024).solve(geolens.circle(300, 300, 110, zoom=4))
    assert result.zoom_fits[0] < 4
    assert result.zoom_measured[0] == pytest.approx(result.zoom_fits[0], rel=0.1)
    assert result.zoom_fit_reasons[0].startswith("the image's ")
    assert result.stats["lenses"][0]["zoom_fit_reason"] == result.zoom_fit_reasons[0]


def test_lens_that_fits_gets_its_zoom_exactly_and_no_reason():
    result = geolens.GeometricLens(4725, 4050).solve(geolens.circle(2362, 2025, 150, zoom=5))
    assert result.zoom_fits[0] == 5
    assert result.zoom_fit_reasons == [""]


def test_warp_arrays_are_read_only_views_of_the_right_shapes(solved):
    warp = solved.warp
    assert warp.F.dtype == np.int32 and warp.F.shape[1] == 3
    assert warp.source.dtype == np.float64 and warp.screen.dtype == np.float64
    assert warp.source.shape == warp.screen.shape == (warp.F.max() + 1, 2)
    assert warp.F.min() == 0
    assert warp.screen_size == (1024, 1024)
    for array in (warp.F, warp.source, warp.screen):
        assert not array.flags.writeable and not array.flags.owndata
    assert np.shares_memory(warp.source, warp.source)  # the same memory each time: a view
    assert solved.stats["vertices"] == warp.source.shape[0]
    assert solved.stats["triangles"] == warp.F.shape[0]


def test_forward_then_inverse_is_the_identity(solved):
    points = np.random.default_rng(1).uniform(0, 1024, size=(2000, 2))
    screen = solved.warp.forward(points)
    assert screen.shape == (2000, 2) and screen.dtype == np.float64
    assert np.isfinite(screen).all()
    assert np.abs(solved.warp.inverse(screen) - points).max() < 1e-6


def test_inverse_then_forward_is_the_identity(solved):
    screen = np.random.default_rng(2).uniform(0, 1024, size=(2000, 2))
    source = solved.warp.inverse(screen)
    assert np.abs(solved.warp.forward(source) - screen).max() < 1e-6


def test_focus_is_magnified_about_its_centre_and_far_points_stay(solved):
    centre, far = np.array([[500.0, 500.0]]), np.array([[20.0, 1000.0]])
    ring = centre + 10 * np.array([[1.0, 0.0]])
    moved = solved.warp.forward(np.vstack([centre, ring, far]))
    assert np.linalg.norm(moved[1] - moved[0]) == pytest.approx(20, rel=0.05)
    assert moved[2] == pytest.approx(far[0], abs=1e-9)


def test_points_outside_the_image_map_to_nan_rows(solved):
    mapped = solved.warp.forward(np.array([[10.0, 10.0], [-50.0, 10.0], [10.0, 2000.0]]))
    assert np.isfinite(mapped[0]).all()
    assert np.isnan(mapped[1:]).all()


def test_bad_points_raise_value_error(solved):
    with pytest.raises(ValueError, match=r"Warp.forward: points must be an N x 2 array"):
        solved.warp.forward(np.zeros(2))
    with pytest.raises(ValueError, match="row 0 .* is neither finite nor a row of NaNs"):
        solved.warp.inverse(np.array([[np.nan, 1.0]]))


def test_forward_and_inverse_chain_through_nan_rows(solved):
    points = np.array([[500.0, 500.0], [-50.0, 10.0]])
    back = solved.warp.inverse(solved.warp.forward(points))
    assert back[0] == pytest.approx(points[0], abs=1e-6)
    assert np.isnan(back[1]).all()


def test_stats_have_the_keys_and_figures_of_the_clis(solved, run_cli):
    cli = run_cli("--lens", "circle:500,500,100:2")
    assert cli.returncode == 0, cli.stderr
    stats = solved.stats
    # "source" says what file the CLI read; a solve from Python reads none.
    assert stats.keys() == cli.stats.keys() - {"source"}
    assert stats["timings_ms"].keys() == cli.stats["timings_ms"].keys()
    assert stats["lenses"][0].keys() == cli.stats["lenses"][0].keys()
    for key in ("vertices", "triangles", "iterations", "flipped", "model", "options"):
        assert stats[key] == cli.stats[key], key


@pytest.mark.parametrize("spec, lens, options", [
    ("circle:500,500,100:2", lambda: geolens.circle(500, 500, 100, zoom=2), {}),
    ("circle:500,500,80:3", lambda: geolens.circle(500, 500, 80, zoom=3), {"mesh": 60}),
    ("polygon:examples/l_polygon.txt:1.6", lambda: geolens.polygon(L_POLYGON, zoom=1.6), {}),
    ("circle:500,500,100:2", lambda: geolens.circle(500, 500, 100, zoom=2),
     {"model": "lift", "mesh": 50}),
])
def test_same_zoom_and_flips_as_the_cli(spec, lens, options, run_cli):
    args = ["--lens", spec]
    for key, value in options.items():
        args += ["--" + key.replace("_", "-"), str(value)]
    cli = run_cli(*args)
    assert cli.returncode == 0, cli.stderr
    stats = geolens.GeometricLens(1024, 1024, **options).solve(lens()).stats
    assert stats["flipped"] == cli.stats["flipped"] == 0
    assert stats["lenses"][0]["zoom_measured"] == pytest.approx(
        cli.stats["lenses"][0]["zoom_measured"], rel=1e-9)
    assert stats["lenses"][0]["zoom_measured"] == pytest.approx(
        stats["lenses"][0]["zoom_requested"], rel=0.1)


def test_bad_options_raise_with_the_clis_message_in_pythons_terms(run_cli):
    # The same problem, the option named as each face names it: --mesh-tolerance, mesh_tolerance.
    for option, value in (("mesh", 2), ("mesh_tolerance", 1e-9), ("subdivide", 9)):
        cli = run_cli("--lens", "circle:500,500,100", "--" + option.replace("_", "-"), str(value))
        with pytest.raises(ValueError) as raised:
            geolens.GeometricLens(1024, 1024, **{option: value})
        assert cli.returncode == 2
        problem = str(raised.value).removeprefix(f"GeometricLens(): {option} ")
        assert problem != str(raised.value)
        assert cli.stderr == f"geolens: error: --{option.replace('_', '-')}: {problem}\n"


def test_lens_outside_the_image_raises_with_the_clis_message(run_cli):
    cli = run_cli("--lens", "circle:5000,1,10")
    with pytest.raises(ValueError) as raised:
        geolens.GeometricLens(1024, 1024).solve(geolens.circle(5000, 1, 10))
    assert cli.stderr == f"geolens: error: {raised.value}\n"


def test_unknown_or_mistyped_options_raise_type_error():
    with pytest.raises(TypeError, match="unexpected keyword argument 'meshes'"):
        geolens.GeometricLens(1024, 1024, meshes=10)
    with pytest.raises(TypeError, match="mesh must be int, got 'fine'"):
        geolens.GeometricLens(1024, 1024, mesh="fine")
    with pytest.raises(ValueError, match="model"):
        geolens.GeometricLens(1024, 1024, model="bulge")


def test_update_follows_a_moving_lens(flips):
    lens = geolens.GeometricLens(1024, 1024)
    for x in (400, 420, 440):
        result = lens.update(geolens.circle(x, 500, 90, zoom=2))
        assert not result.draft
        assert result.zoom_measured[0] == pytest.approx(2, rel=0.1)
        assert flips(result.warp) == 0
        assert result.warp.forward(np.array([[x, 500.0]]))[0] == pytest.approx([x, 500], abs=0.5)
    draft = lens.update(geolens.circle(460, 500, 90, zoom=2), draft=True)
    assert draft.draft and draft.zoom_measured[0] == pytest.approx(2, rel=0.1)
    coarse = geolens.GeometricLens(1024, 1024, draft_mesh=40)
    coarse_draft = coarse.update(geolens.circle(460, 500, 90, zoom=2), draft=True)
    assert coarse_draft.draft and flips(coarse_draft.warp) == 0
    assert coarse_draft.zoom_measured[0] == pytest.approx(2, rel=0.1)
    assert coarse_draft.stats["triangles"] < draft.stats["triangles"] / 3


def test_solves_in_threads_match_the_same_solves_in_turn():
    lens = geolens.GeometricLens(1024, 1024)
    lenses = [geolens.circle(300 + 150 * k, 500, 80, zoom=1.5 + k / 2) for k in range(4)]
    in_turn = [lens.solve(each) for each in lenses]
    in_threads = [None] * len(lenses)

    def solve(k):
        in_threads[k] = lens.solve(lenses[k])

    threads = [threading.Thread(target=solve, args=(k,)) for k in range(len(lenses))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for alone, together in zip(in_turn, in_threads):
        assert np.array_equal(alone.warp.screen, together.warp.screen)
        assert np.array_equal(alone.zoom_measured, together.zoom_measured)


def test_a_solve_in_a_thread_lets_python_run():
    lens = geolens.GeometricLens(1024, 1024, mesh=400, threads=1)
    span, result = {}, {}

    def solve():
        span["start"] = time.perf_counter()
        result["solved"] = lens.solve(geolens.circle(500, 500, 100, zoom=2))
        span["end"] = time.perf_counter()

    thread = threading.Thread(target=solve)
    ticks = []
    thread.start()
    while thread.is_alive():
        ticks.append(time.perf_counter())
    thread.join()
    during = [t for t in ticks if span["start"] <= t <= span["end"]]
    duration = span["end"] - span["start"]
    assert duration > 0.05
    assert len(during) > 2 and np.diff(during).max() < duration / 2
    assert result["solved"].zoom_measured[0] == pytest.approx(2, rel=0.1)
