"""The scene of the YADE comparison (bench/yade): lsdem's side is the lattice the YADE script
builds (lattice.py), and its two inputs are what the docs say: with an overlap every sphere
presses a neighbour or a wall from the first step; touching, none does."""

import sys

import numpy as np
import pytest

import lsdem
from conftest import SOURCE_DIR

sys.path.insert(0, str(SOURCE_DIR / "bench" / "yade"))
import compare  # noqa: E402
import lattice  # noqa: E402


def simulation(overlap):
    text = compare.scene_text("single-node", "one-way", 1, overlap)
    scene = lsdem.Scene.from_text(text, str(SOURCE_DIR / "bench" / "yade" / "lattice.toml"))
    return lsdem.Simulation(scene, threads=2)


@pytest.mark.parametrize("overlap", [0.0, 0.02])
def test_the_grains_and_walls_are_the_lattice_yade_gets(overlap):
    sim = simulation(overlap)
    assert np.array_equal(sim.grains.positions, np.array(lattice.centres(overlap)))
    walls = lattice.walls(overlap)
    # Each outermost sphere reaches past its wall by the overlap, as neighbours overlap.
    positions = sim.grains.positions
    assert positions[:, 0].min() - lattice.RADIUS == pytest.approx(walls["low"] - overlap)
    assert positions[:, 0].max() + lattice.RADIUS == pytest.approx(walls["high"] + overlap)
    assert positions[:, 2].min() - lattice.RADIUS == pytest.approx(walls["floor"] - overlap)
    assert sorted(sim.boundaries) == ["east", "floor", "north", "south", "west"]


def test_with_an_overlap_every_sphere_presses_from_the_first_step():
    sim = simulation(0.02)
    sim.run(steps=1)
    # One-way testing lists a pair's force on the grain that tests it; each sphere tests a
    # neighbour or presses a wall.
    assert set(sim.contacts.grains.tolist()) == set(range(lattice.COUNT ** 3))
    assert sim.energies["elastic"] > 0.0
    for name in ["east", "floor", "north", "south", "west"]:
        assert np.linalg.norm(sim.boundaries[name].reaction) > 0.0


def test_touching_no_sphere_presses():
    sim = simulation(0.0)
    sim.run(steps=1)
    assert len(sim.contacts.points) == 0
    assert sim.energies["elastic"] == 0.0
