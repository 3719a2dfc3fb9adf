"""examples/two_spheres.py runs as a user runs it and writes its plot and table."""

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
