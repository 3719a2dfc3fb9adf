"""No leaks on repeated use: the resident set stays flat over 100 create/destroy cycles of an
asset, a scene, a simulation (with a few steps, views and a checkpoint) and a sample.

Tolerance: after 10 warm-up cycles (allocator pools, TBB's threads and OpenVDB's caches
settle), 100 more may grow the RSS by at most 4 MiB. One leaked simulation world or level set
per cycle would add several MiB per cycle (a 1000-node asset alone is ~0.5 MiB), hundreds
over the run, so the bound catches a per-cycle leak of ~40 KiB or more."""

import gc
import os

import numpy as np

import lsdem
from conftest import SCENES

PAGE = os.sysconf("SC_PAGE_SIZE")
TOLERANCE_BYTES = 4 * 1024 * 1024


def resident_bytes():
    """The resident set size, from /proc/self/statm (second field, in pages)."""
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * PAGE


def cycle(scene_text, points, checkpoint):
    asset = lsdem.bake_sphere(5.0, voxel=1.0, nodes=60)
    phi, grad = asset.sample(points)
    positions = asset.nodes.positions
    scene = lsdem.Scene.from_text(scene_text, str(SCENES / "memory.toml"))
    scene.end_time = 0.0
    scene.end_steps = 5
    sim = lsdem.Simulation(scene, threads=2)
    sim.run(callback=lambda s: s.grains.positions)
    sim.checkpoint(checkpoint)
    contacts = sim.contacts
    try:
        lsdem.load("/nonexistent.vdb")
    except lsdem.Error:
        pass
    del asset, phi, grad, positions, scene, sim, contacts


def test_rss_is_stable_over_100_cycles(tmp_path):
    # The bounce scene with its ball loaded from a file rather than baked at every load.
    ball = tmp_path / "ball.vdb"
    lsdem.bake_sphere(5.0, voxel=0.5, nodes=300).save(str(ball))
    text = (SCENES / "bounce.toml").read_text()
    start = text.index("[assets.ball]")
    end = text.index("[materials.steel]")
    text = text[:start] + f'[assets.ball]\nfile = "{ball}"\n\n' + text[end:]
    points = np.random.default_rng(3).uniform(-6, 6, size=(2000, 3))
    checkpoint = str(tmp_path / "c.lsdem")
    for _ in range(10):
        cycle(text, points, checkpoint)
    gc.collect()
    before = resident_bytes()
    for _ in range(100):
        cycle(text, points, checkpoint)
    gc.collect()
    growth = resident_bytes() - before
    print(f"RSS growth over 100 cycles: {growth / 1024:.0f} KiB")
    assert growth < TOLERANCE_BYTES, f"RSS grew by {growth / 1024:.0f} KiB"
