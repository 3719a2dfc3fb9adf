#!/usr/bin/env python3
"""Micromechanics of a compressed stack, from Python: the 27-sphere stack of
assets/scenes/cube27.toml pressed by its top wall, stopped every few hundred steps to read
the Love–Weber stress, the fabrics of the contact normals, of the branch vectors and of the
normal forces, the mechanical coordination, and each grain's non-affine displacement D²min
since the start (docs/micromechanics.md).

    PYTHONPATH=build/python /usr/bin/python3 examples/micromechanics.py

Units: mm, tonne, s, N (stresses in MPa). Prints a row per stop. A few seconds on 2 cores.
lsdem-run writes the same over a run with `[output] micromechanics = true`
(micromechanics.csv, and each grain's measures in the ParaView frames).
"""

import argparse
import pathlib

import numpy as np

import lsdem

SCENE = pathlib.Path(__file__).resolve().parent.parent / "assets" / "scenes" / "cube27.toml"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stops", type=int, default=5, help="how many times to stop and measure")
    parser.add_argument("--steps", type=int, default=400, help="steps between stops")
    args = parser.parse_args()

    scene = lsdem.Scene.from_toml(str(SCENE))
    sim = lsdem.Simulation(scene, threads=2)
    start = sim.grains.positions.copy()
    radii = np.full(len(start), 5.0)  # the stack's spheres
    print("step  sigma_zz MPa  Z_m   normals' a  branches' a  forces' a  mean f_n N  max D2min mm2")
    for _ in range(args.stops):
        sim.run(steps=args.steps)
        m = sim.micromechanics()
        height = 30.0 + sim.boundaries["top"].displacement[2]  # the box: 30 x 30, its lid moves
        stress = m["stress_moment"] / (30.0 * 30.0 * height)
        d2 = lsdem.nonaffine_displacement(start, sim.grains.positions, radii)
        print(f"{sim.step:5d}  {stress[2, 2]:12.4g}  {m['mechanical_coordination']:4.2f}  "
              f"{m['fabric_anisotropy']:10.3f}  {m['branch_anisotropy']:11.3f}  "
              f"{m['force_anisotropy']:9.3f}  {m['mean_normal_force']:10.4g}  {d2.max():13.3g}")


if __name__ == "__main__":
    main()
