#!/usr/bin/python3
"""Plots of lsdem-study two-spheres (like Feldfogel et al. 2024, Fig. 1C, 1D, 3A, 3B).

usage: two_spheres.py two_spheres.csv OUT_DIR
Each PNG is written to a temporary name and renamed, so a failed run leaves no half image.
"""
import sys
from collections import defaultdict

from plotting import plt, read_numbers, save


def curves(rows, formulation, key):
    """Group P–δ curves of one formulation by node count or stiffness."""
    groups = defaultdict(list)
    for r in rows:
        if r["formulation"] == formulation:
            groups[(r[key], r["nodes"] if key == "kn" else r["kn"])].append(r)
    return groups


def base_stiffness(rows, formulation):
    ks = [r["kn"] for r in rows if r["formulation"] == formulation]
    return max(set(ks), key=ks.count) if ks else None


def plot_family(rows, formulation, by, out_dir, name, title):
    base = base_stiffness(rows, formulation)
    if base is None:
        return
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    if by == "nodes":
        sel = [r for r in rows if r["formulation"] == formulation and r["kn"] == base]
        keys = sorted({r["nodes"] for r in sel})
        for n in keys:
            c = sorted((r for r in sel if r["nodes"] == n), key=lambda r: r["delta"])
            label = "N = %d" % round(c[0]["nodes_actual"])
            ax.plot([r["delta"] for r in c], [r["P"] for r in c], marker="o", ms=3, label=label)
            ax.fill_between([r["delta"] for r in c], [r["P_min"] for r in c],
                            [r["P_max"] for r in c], alpha=0.15)
        if sel[0]["converges"]:  # the law's own continuum limit
            c = sorted((r for r in sel if r["nodes"] == keys[-1]), key=lambda r: r["delta"])
            ax.plot([r["delta"] for r in c], [r["P_exact"] for r in c], "k--", label="exact (continuum)")
    else:
        sel = [r for r in rows if r["formulation"] == formulation]
        counts = defaultdict(set)
        for r in sel:
            counts[r["nodes"]].add(r["kn"])
        n = max(counts, key=lambda k: len(counts[k]))
        if len(counts[n]) < 2:
            plt.close(fig)
            return
        for k in sorted(counts[n]):
            c = sorted((r for r in sel if r["nodes"] == n and r["kn"] == k), key=lambda r: r["delta"])
            ax.plot([r["delta"] for r in c], [r["P"] for r in c], marker="o", ms=3,
                    label="k = %.3g" % k)
        title += " (N = %d)" % round(c[0]["nodes_actual"])
    unit = next(r["kn_unit"] for r in rows if r["formulation"] == formulation)
    ax.set_xlabel("δ [mm]")
    ax.set_ylabel("P [N]")
    ax.set_title("%s: %s, k in %s" % (formulation, title, unit), fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    save(fig, out_dir, name)


def plot_convergence(rows, out_dir):
    """Left: P(δ_max) vs N for each formulation (log-log). Right: the adapted formulation's
    relative error against the exact continuum value."""
    dmax = max(r["delta"] for r in rows)
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.2))
    adapted = []
    for formulation in sorted({r["formulation"] for r in rows}):
        base = base_stiffness(rows, formulation)
        sel = sorted((r for r in rows if r["formulation"] == formulation and r["kn"] == base
                      and abs(r["delta"] - dmax) < 1e-12), key=lambda r: r["nodes_actual"])
        if not sel:
            continue
        left.plot([r["nodes_actual"] for r in sel], [r["P"] for r in sel], marker="o",
                  label="%s (k = %.3g)" % (formulation, base))
        if formulation == "adapted":
            adapted = sel
            left.axhline(sel[0]["P_exact"], color="k", ls="--", label="exact continuum (adapted)")
    left.set_xscale("log")
    left.set_yscale("log")
    left.set_xlabel("surface nodes N")
    left.set_ylabel("P(δ = %.3g mm) [N]" % dmax)
    left.set_title("force at δ_max: original grows ∝ N, adapted converges", fontsize=9)
    left.grid(alpha=0.3, which="both")
    left.legend(fontsize=7)
    if adapted:
        err = [abs(r["P"] / r["P_exact"] - 1) * 100 for r in adapted]
        spread = [(r["P_max"] - r["P_min"]) / r["P_exact"] * 50 for r in adapted]
        right.errorbar([r["nodes_actual"] for r in adapted], err, yerr=spread, marker="o",
                       capsize=3, label="|P/P_exact - 1| (bars: half spread over orientations)")
        right.set_xscale("log")
        right.set_yscale("log")
        right.set_xlabel("surface nodes N")
        right.set_ylabel("relative error [%]")
        right.axhline(1.0, color="grey", ls=":", label="1 %")
        right.set_title("adapted formulation vs exact continuum value", fontsize=9)
        right.grid(alpha=0.3, which="both")
        right.legend(fontsize=7)
    else:
        right.axis("off")
    save(fig, out_dir, "two_spheres_convergence.png")


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    rows = read_numbers(sys.argv[1], text=("formulation", "kn_unit"), whole=("nodes", "converges"))
    out_dir = sys.argv[2]
    for formulation, tag in (("original", "fig1"), ("adapted", "fig3"),
                             ("single-node", "single_node"), ("volume", "volume")):
        plot_family(rows, formulation, "nodes", out_dir, "two_spheres_%s_%s_by_nodes.png" % (tag, formulation),
                    "P–δ per node count")
        plot_family(rows, formulation, "kn", out_dir, "two_spheres_%s_%s_by_stiffness.png" % (tag, formulation),
                    "P–δ per stiffness")
    plot_convergence(rows, out_dir)
    return 0


if __name__ == "__main__":
    sys.exit(main())
