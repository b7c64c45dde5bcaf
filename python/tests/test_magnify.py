"""magnify(), render(), the classic lenses, compare() and the image files."""

import warnings

import geolens
import numpy as np
import pytest


def test_magnify_gives_the_clis_picture(demo, run_cli):
    cli = run_cli("--lens", "circle:500,500,100:2", "--size", "512x512")
    assert cli.returncode == 0, cli.stderr
    out = geolens.magnify(demo, geolens.circle(500, 500, 100, zoom=2), size=(512, 512))
    assert out.shape == cli.image.shape == (512, 512, 3)
    assert out.dtype == np.uint8
    assert np.abs(out.astype(int) - cli.image.astype(int)).mean() < 0.5


def test_magnify_with_options_gives_the_clis_picture(demo, run_cli):
    cli = run_cli("--lens", "circle:300,700,90:2.5", "--model", "lift", "--mesh", "60",
                  "--profile", "mesa")
    assert cli.returncode == 0, cli.stderr
    out = geolens.magnify(demo, [geolens.circle(300, 700, 90, zoom=2.5, profile="mesa")],
                          model="lift", mesh=60)
    assert np.abs(out.astype(int) - cli.image.astype(int)).mean() < 0.5


def test_magnify_keeps_the_dtype_and_channels(demo):
    lens = geolens.circle(500, 500, 100)
    grey = np.ascontiguousarray(demo[:, :, 0])
    rgba = np.dstack([demo, np.full(demo.shape[:2], 200, np.uint8)])
    assert geolens.magnify(grey, lens).shape == (1024, 1024)
    out = geolens.magnify(rgba, lens, size=(300, 200))
    assert out.shape == (200, 300, 4) and out.dtype == np.uint8
    assert (out[:, :, 3] == 200).all()


def test_magnify_leaves_the_image_beyond_the_footprint_alone(demo):
    out = geolens.magnify(demo, geolens.circle(500, 500, 60, zoom=2))
    assert np.array_equal(out[:200, :200], demo[:200, :200])
    assert not np.array_equal(out[450:550, 450:550], demo[450:550, 450:550])


def test_magnify_reads_any_strides(demo):
    lens = geolens.circle(500, 500, 100)
    flipped = demo[:, ::-1]
    assert not flipped.flags.c_contiguous
    assert np.array_equal(geolens.magnify(flipped, lens),
                          geolens.magnify(np.ascontiguousarray(flipped), lens))


def test_magnify_takes_a_mask_and_other_lenses_together(demo):
    mask = np.zeros(demo.shape[:2], dtype=bool)
    mask[700:760, 200:300] = True
    out = geolens.magnify(demo, [geolens.mask(mask, zoom=1.5), geolens.circle(700, 300, 80)])
    assert out.shape == demo.shape


def test_render_of_a_solved_warp_is_magnify(demo):
    lens = geolens.circle(500, 500, 100, zoom=2)
    warp = geolens.GeometricLens(1024, 1024).solve(lens).warp
    assert np.array_equal(geolens.render(warp, demo, (512, 512)),
                          geolens.magnify(demo, lens, size=(512, 512)))
    assert geolens.render(warp, demo).shape == (1024, 1024, 3)


@pytest.mark.parametrize("image, message", [
    (np.zeros((10, 10, 3), np.float32), "uint8 array, got a float32 array of shape"),
    (np.zeros((10, 10, 5), np.uint8), r"got a uint8 array of shape \(10, 10, 5\)"),
    (np.zeros(10, np.uint8), r"shape \(10,\)"),
])
def test_bad_images_raise_value_error(image, message):
    with pytest.raises(ValueError, match="magnify: image must be an H x W or H x W x C.*"
                                         + message):
        geolens.magnify(image, geolens.circle(5, 5, 2))


def test_bad_lenses_and_sizes_raise_value_error(demo):
    lens = geolens.circle(500, 500, 100)
    with pytest.raises(ValueError, match="magnify: lenses is empty"):
        geolens.magnify(demo, [])
    with pytest.raises(ValueError, match="lenses must be a Lens or a list of them"):
        geolens.magnify(demo, [(500, 500, 100)])
    with pytest.raises(ValueError, match=r"size must be None or \(width, height\)"):
        geolens.magnify(demo, lens, size="512x512")
    with pytest.raises(ValueError, match=r"render: width must be in \[1,"):
        geolens.magnify(demo, lens, size=(0, 10))


@pytest.mark.parametrize("name", geolens.CLASSIC_LENSES)
def test_classic_lens_is_matched_to_the_zoom(name, flips):
    result = geolens.classic_lens(name, geolens.circle(500, 500, 60, zoom=2), 1024, 1024,
                                  mesh=100)
    assert result.zoom_measured.shape == result.zoom_parameter.shape == (1,)
    assert result.zoom_measured[0] == pytest.approx(2, rel=0.01)
    assert flips(result.warp) == 0
    far = np.array([[20.0, 20.0]])
    assert result.warp.forward(far) == pytest.approx(far, abs=1e-9)


def test_classic_lens_refuses_unknown_names_and_polygons():
    with pytest.raises(ValueError, match="unknown lens 'loupe', expected one of zoom_in, "):
        geolens.classic_lens("loupe", geolens.circle(50, 50, 10), 100, 100)
    square = geolens.polygon(np.array([[40, 40], [60, 40], [60, 60], [40, 60]]))
    with pytest.raises(ValueError, match="circle"):
        geolens.classic_lens("fisheye", square, 100, 100)


def test_compare_reports_every_method():
    report = geolens.compare(1024, 1024, geolens.circle(500, 500, 80, zoom=2),
                             baseline_mesh=100, mesh=60)
    names = [method["name"] for method in report["methods"]]
    assert names == ["geometric", *geolens.CLASSIC_LENSES]
    assert all(method["flipped"] == 0 for method in report["methods"])
    assert report["methods"][0]["zoom_center"] == pytest.approx(2, rel=0.1)


def test_images_round_trip_through_png(tmp_path, demo):
    path = tmp_path / "demo.png"
    geolens.save_image(str(path), demo[:100, :80])
    back = geolens.load_image(str(path))
    assert back.shape == (100, 80, 3) and back.dtype == np.uint8
    assert np.array_equal(back, demo[:100, :80])
    # max_pixels: exactly the picture's pixels are read; one fewer is refused, naming the limit.
    assert geolens.load_image(str(path), max_pixels=8000).shape == (100, 80, 3)
    with pytest.raises(ValueError, match=r"80 x 100 pixels is more than the 7999 read \(max_pixels"):
        geolens.load_image(str(path), max_pixels=7999)
    with pytest.raises(ValueError, match="max_pixels must be >= 1, got -3"):
        geolens.load_image(str(path), max_pixels=-3)


def test_image_files_refuse_bad_paths(tmp_path, demo):
    with pytest.raises(ValueError, match=r"\.png, \.jpg"):
        geolens.save_image(str(tmp_path / "out.gif"), demo)
    with pytest.raises(ValueError, match="missing.png"):
        geolens.load_image(str(tmp_path / "missing.png"))
    assert list(tmp_path.iterdir()) == []


def test_magnify_warns_as_the_cli_does_when_a_lens_does_not_get_its_zoom(demo, run_cli):
    cli = run_cli("--lens", "circle:512,512,300:4")
    assert cli.returncode == 0, cli.stderr
    with pytest.warns(UserWarning, match=r"lens 1 gets zoom .* of the 4 asked where it is") as w:
        geolens.magnify(demo, geolens.circle(512, 512, 300, zoom=4))
    assert "geolens: warning: " + str(w[0].message) in cli.stderr


def test_magnify_warns_about_an_option_the_model_does_not_read(demo, run_cli):
    # texture= shapes only the lift model's texture map: the default focus model ignores it.
    cli = run_cli("--lens", "circle:512,512,100:2", "--texture", "mvc")
    assert cli.returncode == 0, cli.stderr
    lens = geolens.circle(512, 512, 100, zoom=2)
    with pytest.warns(UserWarning, match=r"^texture is ignored: only the lift model") as w:
        ignored = geolens.magnify(demo, lens, texture="mvc")
    assert "geolens: warning: --" + str(w[0].message) in cli.stderr
    assert np.array_equal(ignored, geolens.magnify(demo, lens))
    # Read by the lift model: no warning.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        geolens.magnify(demo, lens, model="lift", texture="mvc")
