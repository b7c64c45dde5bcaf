"""Lenses: circle(), polygon(), mask(), and the values they refuse."""

import geolens
import numpy as np
import pytest


def test_circle_keeps_its_values():
    lens = geolens.circle(300, 250, 80, zoom=3, profile="mesa", footprint=5)
    assert (lens.kind, lens.zoom, lens.profile, lens.footprint) == ("circle", 3, "mesa", 5)
    assert lens.peak == (300, 250)
    assert lens.size == 80
    assert lens.bounds == (220, 170, 380, 330)


def test_circle_defaults_are_the_clis():
    lens = geolens.circle(10, 10, 5)
    assert (lens.zoom, lens.profile, lens.footprint) == (2, "gaussian", 0)


def test_polygon_from_an_integer_array():
    points = np.array([[200, 220], [260, 220], [260, 360], [200, 360]], dtype=np.int32)
    lens = geolens.polygon(points, zoom=2.5)
    assert lens.kind == "polygon"
    assert lens.zoom == 2.5
    assert lens.bounds == (200, 220, 260, 360)
    assert lens.size == pytest.approx(30, abs=1)  # the half-width of a 60 px wide strip


def test_mask_gives_one_lens_per_blob_in_raster_order():
    mask = np.zeros((400, 500), dtype=bool)
    mask[300:340, 50:90] = True
    mask[100:150, 300:400] = True
    lenses = geolens.mask(mask, zoom=1.5)
    assert [lens.kind for lens in lenses] == ["mask", "mask"]
    assert [lens.zoom for lens in lenses] == [1.5, 1.5]
    assert lenses[0].bounds == pytest.approx((300, 100, 400, 150), abs=1)
    assert lenses[1].bounds == pytest.approx((50, 300, 90, 340), abs=1)


def test_mask_of_integers_counts_non_zero_as_inside():
    mask = np.zeros((100, 100), dtype=np.uint16)
    mask[20:40, 20:40] = 7
    (lens,) = geolens.mask(mask)
    assert lens.bounds == pytest.approx((20, 20, 40, 40), abs=1)


@pytest.mark.parametrize("zoom", [0.5, 9, float("nan")])
def test_zoom_out_of_range_raises_value_error(zoom):
    with pytest.raises(ValueError, match=r"circle: zoom must be in \[1, 8\]"):
        geolens.circle(10, 10, 5, zoom=zoom)


def test_bad_polygons_raise_value_error():
    with pytest.raises(ValueError, match="at least 3 vertices"):
        geolens.polygon(np.array([[0, 0], [1, 1]]))
    with pytest.raises(ValueError, match=r"N x 2 array of numbers, got a float64 array of "
                                         r"shape \(3, 3\)"):
        geolens.polygon(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="edge 0 .* and edge 2 .* intersect"):
        geolens.polygon(np.array([[0, 0], [10, 10], [10, 0], [0, 20]]))


def test_bad_masks_raise_value_error():
    with pytest.raises(ValueError, match="H x W array of bool or integers, got a float32"):
        geolens.mask(np.ones((10, 10), dtype=np.float32))
    with pytest.raises(ValueError, match="no non-zero pixel"):
        geolens.mask(np.zeros((10, 10), dtype=bool))


def test_unknown_profile_raises_value_error():
    with pytest.raises(ValueError, match="flat"):
        geolens.circle(10, 10, 5, profile="flat")
