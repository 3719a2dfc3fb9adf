#!/usr/bin/python3
"""Plots of lsdem-study triaxial: stress ratio and volumetric strain against axial strain for
every run, and the peak and critical-state friction angles against the node spacing (each
seed's run as a point, the line through their means).

usage: triaxial.py triaxial.csv triaxial_runs.csv OUT_DIR
Each PNG is written to a temporary name and renamed, so a failed run leaves no half image.
"""
import sys

from plotting import plt, read_numbers, save

TEXT = ("formulation", "stage", "consolidated", "path")


def shearing(rows, formulation, sdp, seed):
    return [r for r in rows if r["formulation"] == formulation and r["sdp"] == sdp
            and r["seed"] == seed and r["stage"] == "shearing"]


def mean(values):
    return sum(values) / len(values)


def main(csv_path, runs_path, out_dir):
    rows = read_numbers(csv_path, text=TEXT, whole=())
    runs = read_numbers(runs_path, text=TEXT, whole=())
    formulations = list(dict.fromkeys(r["formulation"] for r in runs))
    sdps = sorted({r["sdp"] for r in runs}, reverse=True)
    seeds = list(dict.fromkeys(r["seed"] for r in runs))
    styles = {"adapted": "-", "original": "--"}
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]

    fig, (ratio, volume) = plt.subplots(1, 2, figsize=(11, 4.2))
    for f in formulations:
        for k, sdp in enumerate(sdps):
            for n, seed in enumerate(seeds):
                curve = shearing(rows, f, sdp, seed)
                if not curve:
                    continue
                # One label per formulation and SDP; the seeds' curves share its colour.
                label = f"{f}, SDP {sdp:g} mm" if n == 0 else None
                if n == 0 and len(seeds) > 1:
                    label += f" ({len(seeds)} seeds)"
                eps = [100 * r["axial_strain"] for r in curve]
                ratio.plot(eps, [r["q_over_p"] for r in curve], styles.get(f, ":"),
                           color=colours[k % len(colours)], label=label, lw=1.2)
                volume.plot(eps, [100 * r["volumetric_strain"] for r in curve],
                            styles.get(f, ":"), color=colours[k % len(colours)], label=label,
                            lw=1.2)
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
        mine = [r for r in runs if r["formulation"] == f]
        x = sorted({r["sdp"] for r in mine})
        for key, marker, name, alpha in (("peak_friction_angle", "o", "peak", 1.0),
                                         ("critical_friction_angle", "s", "critical state", 0.7)):
            # Each seed's run a point; the line through the means at each SDP.
            means = [mean([r[key] for r in mine if r["sdp"] == sdp]) for sdp in x]
            line, = ax.plot(x, means, styles.get(f, ":"), alpha=alpha,
                            label=f"{f}: {name}" + (" (mean of the seeds)" if len(seeds) > 1
                                                     else ""))
            ax.plot([r["sdp"] for r in mine], [r[key] for r in mine], marker,
                    color=line.get_color(), alpha=alpha, linestyle="none")
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
