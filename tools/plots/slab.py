#!/usr/bin/python3
"""Plots of lsdem-study slab (like Feldfogel et al. 2024, Fig. 5E-H and 6).

usage: slab.py OUT_DIR
Reads OUT_DIR/slab.csv, slab_runs.csv and slab_snapshots.csv; writes
  slab_sdp.png          P-delta per SDP at the fixed VDP, one panel per formulation (Fig. 5E-H, 6A)
  slab_vdp.png          P-delta per VDP at the converged SDP, adapted (Fig. 6B)
  slab_convergence.png  peak P and the difference to the finest run against SDP and VDP
  slab_blocks.png       the central block's drop and the largest other displacement against delta
  slab_snapshots_coarse.png, slab_snapshots_converged.png   the panel at the snapshot deltas
                        (Fig. 6C, 6D), blocks coloured by how far they moved
Each PNG is written to a temporary name and renamed, so a failed run leaves no half image.
"""
import os
import sys
from collections import defaultdict

from plotting import plt, read_csv, save
from matplotlib import cm, colors
from mpl_toolkits.mplot3d.art3d import Poly3DCollection


def curves_by_run(rows):
    out = defaultdict(lambda: ([], [], [], []))
    for r in rows:
        d, p, drop, others = out[int(r["run"])]
        d.append(float(r["delta"]))
        p.append(float(r["P"]))
        drop.append(float(r["central_drop"]))
        others.append(float(r["others_max"]))
    return out


def label(run):
    return "SDP %g, VDP %g mm (%s nodes)" % (float(run["sdp"]), float(run["vdp"]), run["nodes"])


def plot_sdp(runs, curves, out_dir):
    stage = [r for r in runs if r["diff_sdp_series"] != ""]
    forms = sorted({r["formulation"] for r in stage}, key=lambda f: (f != "adapted", f))
    if not forms:
        return
    fig, axes = plt.subplots(1, len(forms), figsize=(5.6 * len(forms), 4.2), squeeze=False)
    for ax, form in zip(axes[0], forms):
        mine = sorted([r for r in stage if r["formulation"] == form], key=lambda r: -float(r["sdp"]))
        cmap = plt.get_cmap("viridis")
        for k, r in enumerate(mine):
            d, p, _, _ = curves[int(r["run"])]
            ax.plot(d, p, color=cmap(k / max(1, len(mine) - 1)), label=label(r))
        ax.set_xlabel("indenter displacement δ [mm]")
        ax.set_ylabel("P [N]")
        ax.set_title("%s: SDP refined at VDP = %s mm" % (form, mine[0]["vdp"]))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    save(fig, out_dir, "slab_sdp.png")


def plot_vdp(runs, curves, out_dir):
    stage = sorted([r for r in runs if r["diff_vdp_series"] != ""], key=lambda r: -float(r["vdp"]))
    if not stage:
        return
    fig, ax = plt.subplots(figsize=(5.8, 4.2))
    cmap = plt.get_cmap("plasma")
    for k, r in enumerate(stage):
        d, p, _, _ = curves[int(r["run"])]
        ax.plot(d, p, color=cmap(k / max(1, len(stage))), label=label(r))
    ax.set_xlabel("indenter displacement δ [mm]")
    ax.set_ylabel("P [N]")
    ax.set_title("adapted: VDP refined at SDP = %s mm" % stage[0]["sdp"])
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    save(fig, out_dir, "slab_vdp.png")


def plot_convergence(runs, out_dir):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    ax = axes[0]
    for form, marker in (("adapted", "o"), ("original", "s"), ("volume", "^"), ("single-node", "v")):
        mine = sorted([r for r in runs if r["diff_sdp_series"] != "" and r["formulation"] == form],
                      key=lambda r: float(r["sdp"]))
        if mine:
            ax.plot([float(r["sdp"]) for r in mine], [float(r["P_max"]) for r in mine],
                    marker=marker, label=form + " (VDP %s mm)" % mine[0]["vdp"])
    ax.set_xscale("log")
    ax.invert_xaxis()
    ax.set_xlabel("SDP (mean node spacing target) [mm], finer to the right")
    ax.set_ylabel("peak P [N]")
    ax.set_title("peak force against surface refinement")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    ax = axes[1]
    for key, marker in (("sdp", "o"), ("vdp", "s")):
        column = "diff_%s_series" % key
        mine = sorted([r for r in runs if r[column] != "" and r["formulation"] == "adapted"],
                      key=lambda r: float(r[key]))
        mine = [r for r in mine if float(r[column]) > 0]  # the finest is the reference
        if mine:
            ax.plot([float(r[key]) for r in mine], [float(r[column]) for r in mine],
                    marker=marker, label="adapted, %s refined (against the finest)" % key.upper())
    converged = [r for r in runs if r["role"] == "converged"]
    verdict = None  # the legend's title, so the two never overlap
    if converged:
        c = converged[0]
        verdict = "converged: SDP %s, VDP %s mm, VDP/SDP = %.2f" % (
            c["sdp"], c["vdp"], float(c["vdp"]) / float(c["sdp"]))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.invert_xaxis()
    ax.set_xlabel("SDP or VDP [mm], finer to the right")
    ax.set_ylabel("difference to the finest run / its peak P\n(larger of loading-branch RMS and peak)")
    ax.set_title("convergence of the P–δ curve")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, title=verdict, title_fontsize=8)
    save(fig, out_dir, "slab_convergence.png")


def plot_blocks(runs, curves, out_dir):
    chosen = [r for r in runs if r["role"] in ("coarse", "converged")]
    if not chosen:
        return
    fig, ax = plt.subplots(figsize=(5.8, 4.2))
    for r, color in zip(chosen, ("tab:red", "tab:blue")):
        d, _, drop, others = curves[int(r["run"])]
        ax.plot(d, drop, color=color, label="central block, %s: %s" % (r["role"], label(r)))
        ax.plot(d, others, color=color, ls="--", label="largest other block, %s" % r["role"])
    ax.set_xlabel("indenter displacement δ [mm]")
    ax.set_ylabel("block displacement [mm]")
    ax.set_title("failure mode: push-out vs the panel moving as a whole")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    save(fig, out_dir, "slab_blocks.png")


def plot_snapshots(rows, out_dir):
    by_role = defaultdict(lambda: defaultdict(list))
    labels = {}
    for r in rows:
        by_role[r["role"]][float(r["delta"])].append(r)
        labels[r["role"]] = r["label"]
    for role, frames in by_role.items():
        deltas = sorted(frames)
        dmax = max(float(r["displacement"]) for rs in frames.values() for r in rs)
        # Colours up to the thickness (a block pushed out falls much further): the same scale
        # for the coarse and the converged run.
        first = frames[deltas[0]]
        zs0 = [float(r["z%d" % c]) for r in first for c in range(4)]
        thickness = max(zs0) - min(zs0)
        norm = colors.Normalize(0.0, max(thickness, 1e-9), clip=True)
        cmap = plt.get_cmap("viridis")
        xs = [float(r[k]) for rs in frames.values() for r in rs for k in ("x0", "x1", "x2", "x3")]
        zs = [float(r[k]) for rs in frames.values() for r in rs for k in ("z0", "z1", "z2", "z3")]
        half = max(abs(min(xs)), abs(max(xs)))
        # Rows of 3 or 4, whichever leaves fewer empty places (6 snapshots: 2 rows of 3).
        cols = min(len(deltas), min((4, 3), key=lambda c: (-len(deltas) % c, -c)))
        rows_n = (len(deltas) + cols - 1) // cols
        fig = plt.figure(figsize=(4.2 * cols, 3.0 * rows_n))
        for k, delta in enumerate(deltas):
            ax = fig.add_subplot(rows_n, cols, k + 1, projection="3d")
            polys, face_colors = [], []
            for r in frames[delta]:
                polys.append([(float(r["x%d" % c]), float(r["y%d" % c]), float(r["z%d" % c]))
                              for c in range(4)])
                face_colors.append(cmap(norm(float(r["displacement"]))))
            ax.add_collection3d(Poly3DCollection(polys, facecolors=face_colors,
                                                 edgecolors="k", linewidths=0.2))
            ax.set_xlim(-half, half)
            ax.set_ylim(-half, half)
            ax.set_zlim(min(zs), max(max(zs), min(zs) + 1e-6))
            ax.set_box_aspect((1, 1, max(0.25, (max(zs) - min(zs)) / (2 * half))), zoom=1.2)
            ax.view_init(elev=-22, azim=-60)  # from below: a pushed-out block hangs out
            ax.set_title("δ = %.2f mm" % delta, fontsize=9)
            ax.set_axis_off()
        fig.suptitle("%s: %s (seen from below; largest displacement %.2f mm)"
                     % (role, labels[role], dmax), fontsize=10)
        mappable = cm.ScalarMappable(norm=norm, cmap=cmap)
        fig.colorbar(mappable, ax=fig.get_axes(), shrink=0.6, extend="max",
                     label="block displacement [mm] (up to the thickness)")
        save(fig, out_dir, "slab_snapshots_%s.png" % role)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out_dir = sys.argv[1]
    curves = curves_by_run(read_csv(os.path.join(out_dir, "slab.csv")))
    runs = read_csv(os.path.join(out_dir, "slab_runs.csv"))
    plot_sdp(runs, curves, out_dir)
    plot_vdp(runs, curves, out_dir)
    plot_convergence(runs, out_dir)
    plot_blocks(runs, curves, out_dir)
    plot_snapshots(read_csv(os.path.join(out_dir, "slab_snapshots.csv")), out_dir)


if __name__ == "__main__":
    main()
