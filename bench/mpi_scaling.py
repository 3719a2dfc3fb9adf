#!/usr/bin/python3
"""Strong scaling of one lsdem-run simulation over threads and MPI ranks (docs/scaling.md).

A settled heap of the bundled sand grains at 1,000, 10,000 and 100,000 grains, each stepped
from rest on 1 process x 1 thread, 1 process x 2 threads and 2 ranks x 1 thread (and
whatever --configs names); lsdem-run's own summary gives the ms per step and, under mpirun,
the bytes exchanged and the time spent exchanging. Run from the repository:

    /usr/bin/python3 bench/mpi_scaling.py --out results/mpi-scaling

Settling a loose lattice of 100,000 grains would take hours, so, as bench_scale does, a tile
of 250 grains (a loose lattice of the 16 sand grains, randomly turned) settles once under
100 g in its own box, and settled tiles stand side by side (2x2, 8x5, 20x20) in one box of
walls under plain gravity. Units: mm, tonne, s, N (as assets/scenes/sand.toml).
"""

import argparse
import csv
import math
import os
import random
import re
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TILE_COUNT = (5, 5, 10)       # grains per tile along x, y, z
TILE_SPACING = 1.9            # mm between lattice points: clear of each other however turned
ASSETS = 16                   # assets/meshes/sand/grain_0000 ... 0015
TIME = "/usr/bin/time"         # GNU time (Debian package time), if installed
LAYOUTS = {1000: (2, 2), 10000: (8, 5), 100000: (20, 20)}  # tiles along x, y

SCENE_HEAD = """# Made by bench/mpi_scaling.py. Units: mm, tonne, s, N.
[asset_sets.sand]
glob = "{sand}/*.obj"
voxel = 0.04
nodes = 400

[materials.quartz]
density = 2.65e-9

[materials.wall]
density = 0.0

[[contacts]]
materials = ["quartz", "quartz"]
formulation = "adapted"
normal_stiffness = 1e3
shear_stiffness = 5e2
friction = 0.5
restitution = 0.3

[[contacts]]
materials = ["quartz", "wall"]
formulation = "adapted"
normal_stiffness = 1e3
shear_stiffness = 5e2
friction = 0.5
restitution = 0.3

[[grain_files]]
file = "{grains}"
material = "quartz"
"""

WALL = """
[[boundaries]]
name = "{name}"
type = "plane"
material = "wall"
point = [{px}, {py}, 0]
normal = [{nx}, {ny}, {nz}]
"""

SIMULATION = """
[simulation]
gravity = [0, 0, {gz}]
global_damping = 0.1
time_step = "auto"
end_time = {end}

[output]
history_every = 1000000
"""


def random_quaternion(rng):
    """A uniformly random unit quaternion (Shoemake's method)."""
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    return (b * math.cos(2 * math.pi * u3), a * math.sin(2 * math.pi * u2),
            a * math.cos(2 * math.pi * u2), b * math.sin(2 * math.pi * u3))


def write_scene(path, grains_file, box, gravity, end_time):
    """A scene of the grains in @a grains_file in a box [0, box[0]] x [0, box[1]], open on top."""
    text = SCENE_HEAD.format(sand=os.path.join(REPO, "assets", "meshes", "sand"),
                             grains=os.path.basename(grains_file))
    walls = [("floor", 0, 0, 0, 0, 1), ("west", 0, 0, 1, 0, 0), ("east", box[0], 0, -1, 0, 0),
             ("south", 0, 0, 0, 1, 0), ("north", 0, box[1], 0, -1, 0)]
    for name, px, py, nx, ny, nz in walls:
        text += WALL.format(name=name, px=px, py=py, nx=nx, ny=ny, nz=nz)
    text += SIMULATION.format(gz=gravity, end=end_time)
    with open(path, "w") as f:
        f.write(text)


def write_grains(path, rows):
    columns = ["name", "asset", "x", "y", "z", "qw", "qx", "qy", "qz"]
    with open(path, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(columns)
        for r in rows:
            out.writerow([r[c] for c in columns])


def run(command, log, env=None):
    """Run @a command, its output into @a log; the output, or exit naming the log."""
    started = time.time()
    with open(log, "w") as f:
        done = subprocess.run(command, stdout=f, stderr=subprocess.STDOUT, env=env)
    text = open(log).read()
    # --stop-at-step ends a run as a stop request does: exit code 130, checkpoint written.
    if done.returncode not in (0, 130) or (done.returncode == 130 and "stopped at" not in text):
        sys.exit("mpi_scaling: failed (exit %d): %s\n  see %s" %
                 (done.returncode, " ".join(command), log))
    return text, time.time() - started


def settled_tile(args, lsdem_run):
    """The 250-grain tile after settling: its rows (name, asset, pose) and its box size."""
    folder = os.path.join(args.out, "tile")
    os.makedirs(folder, exist_ok=True)
    rng = random.Random(1)
    rows = []
    nx, ny, nz = TILE_COUNT
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                q = random_quaternion(rng)
                index = len(rows)
                rows.append({"name": "g%d" % index, "asset": "sand/grain_%04d" % (index % ASSETS),
                             "x": (i + 0.5) * TILE_SPACING, "y": (j + 0.5) * TILE_SPACING,
                             "z": (k + 0.5) * TILE_SPACING,
                             "qw": q[0], "qx": q[1], "qy": q[2], "qz": q[3]})
    box = (nx * TILE_SPACING, ny * TILE_SPACING)
    write_grains(os.path.join(folder, "lattice.csv"), rows)
    scene = os.path.join(folder, "tile.toml")
    write_scene(scene, "lattice.csv", box, -981000, 1.0)
    final = os.path.join(folder, "run", "grains.csv")
    if not os.path.exists(final):
        print("settling the 250-grain tile (%d steps under 100 g) ..." % args.settle_steps,
              flush=True)
        run([lsdem_run, scene, "--out", os.path.join(folder, "run"), "--overwrite",
             "--stop-at-step", str(args.settle_steps)], os.path.join(folder, "settle.log"))
    assets = {r["name"]: r["asset"] for r in rows}
    settled = []
    with open(final) as f:
        for r in csv.DictReader(f):
            settled.append({"name": r["name"], "asset": assets[r["name"]],
                            **{c: r[c] for c in ["x", "y", "z", "qw", "qx", "qy", "qz"]}})
    return settled, box


def heap(args, tile, box, grains):
    """The scene of @a grains grains: settled tiles side by side in one box."""
    tx, ty = LAYOUTS[grains]
    folder = os.path.join(args.out, "heap%d" % grains)
    os.makedirs(folder, exist_ok=True)
    rows = []
    for a in range(tx):
        for b in range(ty):
            for r in tile:
                rows.append({**r, "name": "t%d_%d_%s" % (a, b, r["name"]),
                             "x": float(r["x"]) + a * box[0], "y": float(r["y"]) + b * box[1]})
    write_grains(os.path.join(folder, "grains.csv"), rows)
    scene = os.path.join(folder, "heap.toml")
    write_scene(scene, "grains.csv", (tx * box[0], ty * box[1]), -9810, 1.0)
    return scene


def summary_figures(text):
    """ms/step and the exchange figures from lsdem-run's summary."""
    figures = {}
    m = re.search(r"throughput: (\d+) steps, ([0-9.e+-]+) ms/step", text)
    if m:
        figures["steps"], figures["ms_per_step"] = int(m.group(1)), float(m.group(2))
    m = re.search(r"setup \(assets, scene\)\s+([0-9.]+) s", text)
    if m:
        figures["setup_s"] = float(m.group(1))
    peaks = [int(k) for k in re.findall(r"peak resident memory: (\d+) KiB", text)]
    if peaks:
        figures["peak_MiB_per_rank"] = round(max(peaks) / 1024.0, 1)
    figures["exchange"] = " | ".join(line.strip() for line in text.splitlines()
                                     if re.search(r"exchang|bytes|ghost", line))
    return figures


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(REPO, "build"))
    parser.add_argument("--out", default=os.path.join(REPO, "results", "mpi-scaling"))
    parser.add_argument("--grains", type=int, nargs="+", default=[1000, 10000, 100000],
                        choices=sorted(LAYOUTS))
    parser.add_argument("--steps", type=int, default=200, help="steps timed per run")
    parser.add_argument("--settle-steps", type=int, default=40000)
    parser.add_argument("--configs", nargs="+", default=["1x1", "1x2", "2x1"],
                        help="RANKSxTHREADS")
    parser.add_argument("--repeat", type=int, default=1, help="rounds (medians are printed)")
    args = parser.parse_args()
    args.out = os.path.abspath(args.out)
    lsdem_run = os.path.join(args.build, "tools", "lsdem-run")
    if not os.path.exists(lsdem_run):
        sys.exit("mpi_scaling: %s not found; build first (bash scripts/build.sh)" % lsdem_run)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")

    tile, box = settled_tile(args, lsdem_run)
    results = []
    for grains in args.grains:
        scene = heap(args, tile, box, grains)
        for round_ in range(args.repeat):
            for config in args.configs:
                ranks, threads = (int(x) for x in config.split("x"))
                out = os.path.join(args.out, "heap%d" % grains, "run_%s_%d" % (config, round_))
                # (--overwrite: a round run again replaces its own earlier outputs.)
                command = [lsdem_run, scene, "--out", out, "--overwrite", "--stop-at-step",
                           str(args.steps), "--threads", str(threads)]
                if os.path.exists(TIME):  # each rank's peak resident memory
                    command = [TIME, "-f", "peak resident memory: %M KiB"] + command
                if ranks > 1:
                    command = ["mpirun", "--oversubscribe", "--bind-to", "none", "-n",
                               str(ranks)] + command
                text, wall = run(command, out + ".log", env)
                f = summary_figures(text)
                f.update(grains=grains, ranks=ranks, threads=threads, round=round_,
                         wall_s=round(wall, 2), load=os.getloadavg()[0])
                results.append(f)
                print("%6d grains  %d rank(s) x %d thread(s): %s ms/step, peak %s MiB per rank  %s"
                      % (grains, ranks, threads, f.get("ms_per_step"),
                         f.get("peak_MiB_per_rank"), f["exchange"]), flush=True)
    table = os.path.join(args.out, "scaling.csv")
    columns = ["grains", "ranks", "threads", "round", "ms_per_step", "steps", "setup_s",
               "peak_MiB_per_rank", "wall_s", "load", "exchange"]
    with open(table + ".tmp", "w", newline="") as f:
        out = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        out.writeheader()
        out.writerows(results)
    os.replace(table + ".tmp", table)
    print("medians (ms/step):")
    for grains in args.grains:
        for config in args.configs:
            ranks, threads = (int(x) for x in config.split("x"))
            times = sorted(r["ms_per_step"] for r in results if r["grains"] == grains and
                           r["ranks"] == ranks and r["threads"] == threads and
                           "ms_per_step" in r)
            if times:
                print("  %6d grains  %s: %.3f" % (grains, config, times[len(times) // 2]))
    print("written: %s" % table)


if __name__ == "__main__":
    main()
