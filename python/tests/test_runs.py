"""Whole runs from Python: run_scene writes lsdem-run's files byte for byte, and
study.two_spheres gives the study's rows (and its CSV) with the physics of the two spheres."""

import math
import subprocess

import pytest

import lsdem
from conftest import SCENES


def test_run_scene_writes_lsdem_run_files_byte_for_byte(lsdem_run, tmp_path):
    scene = SCENES / "cube27.toml"
    by_program = tmp_path / "program"
    by_python = tmp_path / "python"
    subprocess.run([lsdem_run, str(scene), "--out", str(by_program), "--threads", "1", "-q"],
                   check=True, stdout=subprocess.DEVNULL)
    result = lsdem.run_scene(scene, by_python, threads=2)

    assert not result["interrupted"]
    assert result["grains"] == 27
    assert result["step"] > 0 and result["time"] > 0
    compared = 0
    for name in ("grains.csv", "energy.csv", "boundary_top.csv"):
        assert (by_python / name).read_bytes() == (by_program / name).read_bytes(), name
        compared += 1
    assert compared == 3


def test_run_scene_stops_at_a_step_with_a_checkpoint(tmp_path):
    result = lsdem.run_scene(SCENES / "bounce.toml", tmp_path, threads=1, stop_at_step=5)
    assert result["interrupted"]
    assert result["step"] == 5
    restarted = lsdem.Simulation.from_checkpoint(result["checkpoint"], threads=1)
    assert restarted.step == 5


def test_run_scene_errors(tmp_path):
    with pytest.raises(lsdem.Error, match="missing.toml"):
        lsdem.run_scene(tmp_path / "missing.toml", tmp_path / "out")
    with pytest.raises(lsdem.Error, match="threads"):
        lsdem.run_scene(SCENES / "bounce.toml", tmp_path / "out", threads=0)


def test_run_scene_refuses_an_earlier_run_unless_overwrite(tmp_path):
    out = tmp_path / "out"
    lsdem.run_scene(SCENES / "bounce.toml", out, threads=1, stop_at_step=5)
    (out / "notes.txt").write_text("mine")
    checkpoint = (out / "checkpoint.lsdem").read_bytes()
    with pytest.raises(lsdem.Error, match="(?s)outputs of an earlier run.*overwrite=True"):
        lsdem.run_scene(SCENES / "bounce.toml", out, threads=1, stop_at_step=7)
    assert (out / "checkpoint.lsdem").read_bytes() == checkpoint

    result = lsdem.run_scene(SCENES / "bounce.toml", out, threads=1, stop_at_step=7,
                             overwrite=True)
    assert result["step"] == 7
    assert lsdem.Simulation.from_checkpoint(result["checkpoint"], threads=1).step == 7
    assert (out / "notes.txt").read_text() == "mine"


def test_two_spheres_rows_follow_the_continuum_limit(tmp_path):
    rows = lsdem.study.two_spheres(formulations=["adapted", "original"], nodes=[500, 2000],
                                   stiffness_factors=[1.0], radius=5.0, voxel=0.1,
                                   delta_max=0.1, steps=2, orientations=1,
                                   out_dir=tmp_path)
    # 2 formulations x 2 node counts x 3 values of delta (0, 0.05, 0.1).
    assert len(rows) == 12
    assert {r["formulation"] for r in rows} == {"adapted", "original"}
    for r in rows:
        # The adapted formulation's continuum limit (SCIENCE.md) is the exact traction
        # integral; to leading order in delta/R = 0.02 it is pi kn* R delta^2 / 2.
        leading = math.pi * r["stiffness"] * 5.0 * r["delta"] ** 2 / 2
        assert r["force_exact"] == pytest.approx(leading, rel=0.01, abs=1e-12)
    adapted = {r["nodes"]: r for r in rows if r["formulation"] == "adapted" and r["delta"] > 0.09}
    original = {r["nodes"]: r for r in rows if r["formulation"] == "original" and r["delta"] > 0.09}
    # Adapted converges to the continuum force: a few nodes share the contact disc (radius
    # sqrt(R delta) = 0.7 mm) at N = 500, some tens at N = 2000 ...
    error = {n: abs(r["force"] / r["force_exact"] - 1) for n, r in adapted.items()}
    assert error[2000] < 0.03
    assert error[2000] < error[500]
    # ... while original, summing kn*d per node, stiffens with the node count (about 4x).
    assert original[2000]["force"] / original[500]["force"] > 2.5
    # The CSV written beside holds the same rows.
    lines = (tmp_path / "two_spheres.csv").read_text().splitlines()
    assert lines[1].startswith("formulation,nodes,")
    assert len(lines) == 2 + len(rows)


def test_two_spheres_bad_input():
    with pytest.raises(lsdem.Error):
        lsdem.study.two_spheres(formulations=["nonsense"], nodes=[500])
    with pytest.raises(lsdem.Error, match="delta"):
        lsdem.study.two_spheres(nodes=[500], radius=0.05, delta_max=0.1)
