#!/usr/bin/env python3
"""Two equal spheres pressed together, from Python: bake a sphere grain, build the scene in
Python (one sphere fixed, the other pushed along the centre line at a prescribed speed), step
it with a callback that records the force on the fixed sphere, and plot P against the
overlap δ with matplotlib. The lsdem-study two-sphere study does the same with more node
counts and orientations (docs/contact.md).

    PYTHONPATH=build/python /usr/bin/python3 examples/two_spheres.py --out results/python

Units: mm, tonne, s, N (stiffness kn* in N/mm³). Writes two_spheres.png and two_spheres.csv
to --out and prints the last row. About two seconds on 2 cores with the defaults.
"""

import argparse
import math
import os
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

import lsdem  # noqa: E402

RADIUS = 5.0          # mm
STIFFNESS = 1e3       # kn*, N/mm³: the adapted formulation's traction per penetration
DELTA_MAX = 0.1       # mm
STEPS = 50
SPEED = 1.0           # mm/s of the pushed sphere; with prescribed motion only δ matters


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="results/python-two-spheres", help="output folder")
    parser.add_argument("--nodes", type=int, default=2000, help="surface nodes (about)")
    parser.add_argument("--voxel", type=float, default=0.1, help="level-set voxel, mm")
    parser.add_argument("--formulation", default="adapted",
                        help="adapted, original, single-node or volume")
    parser.add_argument("--threads", type=int, default=2)
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)

    sphere = lsdem.bake_sphere(RADIUS, voxel=args.voxel, nodes=args.nodes)
    print(f"baked {sphere}")

    # Touching at the start; the pushed sphere moves by DELTA_MAX in STEPS steps.
    dt = DELTA_MAX / (SPEED * STEPS)
    scene = lsdem.Scene()
    scene.add_asset("sphere", sphere)
    scene.add_material("glass", density=2.5e-9)
    scene.add_contact("glass", "glass", formulation=args.formulation,
                      normal_stiffness=STIFFNESS)
    scene.add_grain("sphere", "glass", [0, 0, 0], motion="fixed", name="fixed")
    scene.add_grain("sphere", "glass", [2 * RADIUS, 0, 0], velocity=[-SPEED, 0, 0],
                    motion="prescribed", name="pushed")
    scene.time_step = dt
    scene.end_steps = STEPS

    sim = lsdem.Simulation(scene, threads=args.threads, record_contacts=False)
    deltas, forces = [0.0], [0.0]

    def record(s):
        # δ from the positions (a view into the running simulation), P on the fixed sphere.
        x = s.grains.positions
        deltas.append(2 * RADIUS - float(np.linalg.norm(x[1] - x[0])))
        forces.append(-float(s.grains.forces[0, 0]))  # pushed along -x: P is -F_x

    sim.run(callback=record)

    # The small-δ continuum limit of the adapted formulation: the traction kn*·(δ - r²/R)
    # integrated over the contact disc r² < Rδ gives P = π kn* R δ² / 2.
    reference = [math.pi * STIFFNESS * RADIUS * d * d / 2 for d in deltas]
    with open(os.path.join(args.out, "two_spheres.csv"), "w") as f:
        f.write("delta_mm,force_N,continuum_N\n")
        for d, p, r in zip(deltas, forces, reference):
            f.write(f"{d!r},{p!r},{r!r}\n")
    print(f"δ = {deltas[-1]:.4g} mm: P = {forces[-1]:.4g} N "
          f"(continuum {reference[-1]:.4g} N, ratio {forces[-1] / reference[-1]:.4f})")

    fig, ax = plt.subplots(figsize=(5, 4))
    ax.plot(deltas, forces, "o-", ms=3, label=f"lsdem {args.formulation}, "
            f"{len(sphere.nodes)} nodes")
    if args.formulation == "adapted":
        ax.plot(deltas, reference, "k--", label=r"$\pi k_n^* R \delta^2 / 2$")
    ax.set_xlabel("δ (mm)")
    ax.set_ylabel("P (N)")
    ax.set_title("Two spheres, R = 5 mm")
    ax.legend()
    fig.tight_layout()
    png = os.path.join(args.out, "two_spheres.png")
    fig.savefig(png, dpi=120)
    print(f"wrote {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
