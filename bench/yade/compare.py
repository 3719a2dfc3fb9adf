#!/usr/bin/env python3
"""lsdem against YADE's level-set DEM on one scene, runs interleaved (this machine is noisy).

The scene: 1000 level-set spheres (radius 1, voxel 0.1, 1000 surface nodes) in a 10 x 10 x 10
lattice in five walls under gravity, each overlapping its neighbours and the walls by --overlap
(0.02: every neighbour a contact; 0: touching): yade_lattice.py for YADE (`apt-get install
yade`), SCENE below for lsdem-run, both from lattice.py. Each round runs YADE once and lsdem once per contact law and
thread count; both time the steps alone (YADE: O.run after a first step; lsdem-run: its
throughput line, setup left out).

    python3 bench/yade/compare.py --rounds 5 [--steps 200] [--threads 1 2]

prints each round and then the medians and the ratios of the medians.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import lattice  # noqa: E402 (the geometry both codes share)
LAWS = [("single-node", "one-way"), ("adapted", "one-way"), ("adapted", "symmetric")]


SCENE = """# 1000 level-set spheres in a lattice in five walls (bench/yade/lattice.py), as
# yade_lattice.py builds them for YADE. Units: mm, tonne, s, N.
[assets.sphere]
shape = "sphere"
radius = {radius!r}
voxel = {voxel!r}
nodes = {nodes}

[materials.grain]
density = {density!r}

[materials.wall]
density = 0.0

[[contacts]]
materials = ["grain", "grain"]
formulation = "{formulation}"
testing = "{testing}"
normal_stiffness = {stiffness!r}

[[contacts]]
materials = ["grain", "wall"]
formulation = "{formulation}"
testing = "{testing}"
normal_stiffness = {stiffness!r}

[[lattices]]
asset = "sphere"
material = "grain"
origin = [0, 0, {radius!r}]
count = [{count}, {count}, {count}]
spacing = [{spacing!r}, {spacing!r}, {spacing!r}]

{boundaries}
[simulation]
gravity = [0, 0, {gravity!r}]
time_step = {dt!r}
end_steps = {steps}
"""


BOUNDARY = """[[boundaries]]
name = "{name}"
type = "plane"
material = "wall"
point = {point}
normal = {normal}
"""


def scene_text(formulation, testing, steps, overlap):
    """The scene of yade_lattice.py for lsdem-run, with the given law (grains and walls)."""
    boundaries = "\n".join(BOUNDARY.format(name=name, point=list(point), normal=list(normal))
                           for name, point, normal in lattice.planes(overlap))
    return SCENE.format(radius=lattice.RADIUS, voxel=lattice.GRID_SPACING, nodes=lattice.NODES,
                        density=lattice.DENSITY, stiffness=lattice.NORMAL_STIFFNESS,
                        formulation=formulation, testing=testing, count=lattice.COUNT,
                        spacing=lattice.spacing(overlap), boundaries=boundaries,
                        gravity=lattice.GRAVITY, dt=lattice.TIME_STEP, steps=steps)


def lsdem_scene(directory, formulation, testing, steps, overlap):
    """scene_text written to a file in @a directory; its path."""
    path = os.path.join(directory, "lattice_%s_%s.toml" % (formulation, testing))
    with open(path, "w") as f:
        f.write(scene_text(formulation, testing, steps, overlap))
    return path


def run(command, **options):
    """@a command's completed process; a missing program or a failed run stops the script with
    what it printed."""
    try:
        result = subprocess.run(command, capture_output=True, text=True, **options)
    except FileNotFoundError:
        sys.exit("%s not found (lsdem-run: build it first, `bash scripts/demo.sh`; yade: `apt-get install yade`)"
                 % command[0])
    if result.returncode != 0:
        sys.exit("%s failed (exit %d):\n%s%s" % (" ".join(command), result.returncode, result.stdout,
                                                 result.stderr))
    return result


def run_lsdem(binary, scene, out, threads):
    result = run([binary, scene, "--out", out, "--overwrite", "--threads", str(threads), "-q"])
    found = re.search(r"throughput: \d+ steps, ([0-9.]+) ms/step", result.stdout + result.stderr)
    if not found:
        sys.exit("lsdem-run printed no throughput line:\n" + result.stdout + result.stderr)
    return float(found.group(1))


def run_yade(steps, overlap):
    result = run(["yade", "-j1", "-n", "-x", os.path.join(HERE, "yade_lattice.py"), str(steps), repr(overlap)],
                 cwd=tempfile.gettempdir())
    found = re.search(r"([0-9.]+) ms/step, (\d+) interactions", result.stdout)
    if not found:
        sys.exit("yade printed no timing line:\n" + result.stdout + result.stderr)
    return float(found.group(1)), int(found.group(2))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--overlap", type=float, default=0.02,
                        help="each sphere's overlap with its neighbours and the walls (0: touching)")
    parser.add_argument("--lsdem-run", default=os.path.join(ROOT, "build", "tools", "lsdem-run"))
    args = parser.parse_args()
    if args.rounds < 1 or args.steps < 1:
        sys.exit("--rounds and --steps must be at least 1")
    times = {}
    with tempfile.TemporaryDirectory() as work:
        scenes = {law: lsdem_scene(work, law[0], law[1], args.steps, args.overlap) for law in LAWS}
        for r in range(args.rounds):
            yade, contacts = run_yade(args.steps, args.overlap)
            times.setdefault("yade", []).append(yade)
            row = ["round %d: yade %.1f ms (%d interactions)" % (r + 1, yade, contacts)]
            for law in LAWS:
                for threads in args.threads:
                    key = (law, threads)
                    ms = run_lsdem(args.lsdem_run, scenes[law], os.path.join(work, "out"), threads)
                    times.setdefault(key, []).append(ms)
                    row.append("%s %s %dt %.3f" % (law[0], law[1], threads, ms))
            print("; ".join(row), flush=True)
    yade = statistics.median(times["yade"])
    print("\nmedians of %d rounds, %d steps, overlap %g (ms/step):" % (args.rounds, args.steps, args.overlap))
    print("  YADE 2023.02a, 1 thread: %.1f (%.1f-%.1f)" % (yade, min(times["yade"]), max(times["yade"])))
    for law in LAWS:
        for threads in args.threads:
            t = times[(law, threads)]
            m = statistics.median(t)
            line = "  lsdem %-11s %-9s %d thread(s): %.3f (%.3f-%.3f), YADE/lsdem %.0fx" % (
                law[0], law[1], threads, m, min(t), max(t), yade / m)
            if threads != args.threads[0]:
                line += ", over %d thread(s) %.2fx" % (args.threads[0], statistics.median(times[(law, args.threads[0])]) / m)
            print(line)


if __name__ == "__main__":
    main()
