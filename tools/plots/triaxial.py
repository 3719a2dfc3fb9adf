#!/usr/bin/python3
"""Plots of lsdem-study triaxial: stress ratio and volumetric strain against axial strain for
every run, and the peak and critical-state friction angles against the node spacing.

usage: triaxial.py triaxial.csv triaxial_runs.csv OUT_DIR
Each PNG is written to a temporary name and renamed, so a failed run leaves no half image.
"""
import sys

from plotting import plt, read_numbers, save

TEXT = ("formulation", "stage", "consolidated")


def shearing(rows, formulation, sdp):
    return [r for r in rows if r["formulation"] == formulation and r["sdp"] == sdp
            and r["stage"] == "shearing"]


def main(csv_path, runs_path, out_dir):
    rows = read_numbers(csv_path, text=TEXT, whole=())
    runs = read_numbers(runs_path, text=TEXT, whole=())
    formulations = list(dict.fromkeys(r["formulation"] for r in runs))
    sdps = sorted({r["sdp"] for r in runs}, reverse=True)
    styles = {"adapted": "-", "original": "--"}
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]

    fig, (ratio, volume) = plt.subplots(1, 2, figsize=(11, 4.2))
    for f in formulations:
        for k, sdp in enumerate(sdps):
            curve = shearing(rows, f, sdp)
            if not curve:
                continue
            label = f"{f}, SDP {sdp:g} mm"
            eps = [100 * r["axial_strain"] for r in curve]
            ratio.plot(eps, [r["q_over_p"] for r in curve], styles.get(f, ":"),
                       color=colours[k % len(colours)], label=label, lw=1.2)
            volume.plot(eps, [100 * r["volumetric_strain"] for r in curve], styles.get(f, ":"),
                        color=colours[k % len(colours)], label=label, lw=1.2)
    ratio.set_xlabel("axial strain ε_a [%]")
    ratio.set_ylabel("stress ratio q/p")
    volume.set_xlabel("axial strain ε_a [%]")
    volume.set_ylabel("volumetric strain ε_v [%] (compression +)")
    for ax in (ratio, volume):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Triaxial compression: adapted (solid) and original (dashed)", fontsize=10)
    save(fig, out_dir, "triaxial_curves.png")

    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    for f in formulations:
        mine = sorted((r for r in runs if r["formulation"] == f), key=lambda r: r["sdp"])
        x = [r["sdp"] for r in mine]
        ax.plot(x, [r["peak_friction_angle"] for r in mine], "o" + styles.get(f, ":"),
                label=f"{f}: peak")
        ax.plot(x, [r["critical_friction_angle"] for r in mine], "s" + styles.get(f, ":"),
                label=f"{f}: critical state", alpha=0.7)
    ax.set_xlabel("node spacing SDP [mm]")
    ax.set_ylabel("friction angle φ [°]")
    ax.invert_xaxis()
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title("Friction angles as the nodes are refined (finer to the right)", fontsize=9)
    save(fig, out_dir, "triaxial_friction_angles.png")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
