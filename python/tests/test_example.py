"""The examples run as a user runs them: two_spheres.py writes its plot and table,
micromechanics.py prints its rows."""

import csv
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR


def test_two_spheres_example(tmp_path):
    script = SOURCE_DIR / "examples" / "two_spheres.py"
    out = subprocess.run([sys.executable, str(script), "--out", str(tmp_path)], check=True,
                         capture_output=True, text=True).stdout
    assert "wrote" in out
    png = tmp_path / "two_spheres.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with open(tmp_path / "two_spheres.csv", newline="") as f:
        last = list(csv.DictReader(f))[-1]
    assert float(last["delta_mm"]) == pytest.approx(0.1)
    # About 2000 nodes land within a few per cent of the continuum limit.
    assert float(last["force_N"]) == pytest.approx(float(last["continuum_N"]), rel=0.05)


def test_micromechanics_example():
    """examples/micromechanics.py: a row per stop; the stack's vertical stress compressive and
    growing as the lid comes down; every anisotropy within its bound, 15/2 (all along one
    axis)."""
    script = SOURCE_DIR / "examples" / "micromechanics.py"
    out = subprocess.run([sys.executable, str(script), "--stops", "3", "--steps", "400"],
                         check=True, capture_output=True, text=True).stdout
    rows = [line.split() for line in out.splitlines()[1:]]
    assert len(rows) == 3
    sigma = [float(r[1]) for r in rows]
    assert sigma[0] < 0.0 and sigma[2] < sigma[1] < sigma[0]
    for r in rows:
        assert all(0.0 <= float(a) <= 7.5 + 1e-9 for a in r[3:6])
