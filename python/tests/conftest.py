"""Shared fixtures of the Python tests: where the sources and lsdem-run are, and one small
baked sphere (baking is the slow part, so it is done once per test file)."""

import os
import pathlib

import pytest

import lsdem

SOURCE_DIR = pathlib.Path(
    os.environ.get("LSDEM_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
SCENES = SOURCE_DIR / "assets" / "scenes"


@pytest.fixture(scope="module")
def sphere():
    """A sphere of radius 5 (mm) with about 500 nodes on a 0.25 mm level set."""
    return lsdem.bake_sphere(5.0, voxel=0.25, nodes=500)


@pytest.fixture
def lsdem_run():
    """The lsdem-run program of this build (ctest passes its path)."""
    path = os.environ.get("LSDEM_RUN")
    if not path or not os.path.exists(path):
        pytest.skip("LSDEM_RUN does not name the lsdem-run program (run through ctest)")
    return path
