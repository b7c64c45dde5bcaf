"""Fixtures of the geolens module's tests: the demo image and the CLI built with the module."""

import json
import os
import subprocess
from pathlib import Path

import geolens
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
DEMO = ROOT / "examples" / "demo.png"


@pytest.fixture(scope="session")
def demo():
    """examples/demo.png, 1024 x 1024 RGB."""
    return geolens.load_image(str(DEMO))


@pytest.fixture(scope="session")
def cli():
    """The geolens CLI: $GEOLENS_CLI (set by ctest), else the one next to the module."""
    path = Path(os.environ.get("GEOLENS_CLI",
                               Path(geolens.__file__).parents[1] / "geolens"))
    if not path.is_file():
        pytest.skip(f"no geolens CLI at {path}: set GEOLENS_CLI")
    return path


class CliRun:
    """The CLI's magnify on the demo image: its output image and stats."""

    def __init__(self, cli, tmp_path, args):
        output, stats = tmp_path / "out.png", tmp_path / "stats.json"
        done = subprocess.run(
            [str(cli), "magnify", str(DEMO), "-o", str(output), "--stats",
             str(stats), *args], capture_output=True, text=True, check=False)
        self.returncode, self.stderr = done.returncode, done.stderr
        if done.returncode == 0:
            self.image = geolens.load_image(str(output))
            self.stats = json.loads(stats.read_text())


@pytest.fixture
def run_cli(cli, tmp_path):
    """run_cli(*args): the CLI's magnify of the demo image with args."""
    return lambda *args: CliRun(cli, tmp_path, args)


def _flips(warp):
    def signed_areas(points):
        a, b, c = (points[warp.F[:, k]] for k in range(3))
        return np.cross(b - a, c - a)
    return int(np.sum(signed_areas(warp.screen) * signed_areas(warp.source) < 0))


@pytest.fixture(scope="session")
def flips():
    """flips(warp): its triangles whose screen orientation is the opposite of their source's."""
    return _flips
