#!/usr/bin/python3
"""Plots of lsdem-study cube27 (like Feldfogel et al. 2024, Fig. 4B-E).

usage: cube27.py cube27.csv OUT_DIR
Each PNG is written to a temporary name and renamed, so a failed run leaves no half image.
"""
import sys
from collections import defaultdict

from plotting import plt, read_numbers, save


def base_stiffness(rows, formulation):
    """The stiffness of the node-count sweep: the one run at the most node counts."""
    counts = defaultdict(set)
    for r in rows:
        if r["formulation"] == formulation:
            counts[r["kn"]].add(r["nodes"])
    return max(counts, key=lambda k: (len(counts[k]), k)) if counts else None


def curve(rows, formulation, nodes, kn):
    return sorted((r for r in rows if r["formulation"] == formulation and r["nodes"] == nodes
                   and r["kn"] == kn), key=lambda r: r["delta"])


def unit(rows, formulation):
    """The unit of the formulation's stiffness, as the study wrote it (its sub-model's)."""
    return next(r["kn_unit"] for r in rows if r["formulation"] == formulation)


def converges(rows, formulation):
    """Whether the formulation converges to P_exact as the nodes refine (the study's column)."""
    return any(r["converges"] for r in rows if r["formulation"] == formulation)


def finish(ax, title):
    ax.set_xlabel("top wall displacement δ [mm]")
    ax.set_ylabel("top wall force P [N]")
    ax.set_title(title, fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)


def plot_by_nodes(rows, formulation, out_dir, name):
    base = base_stiffness(rows, formulation)
    if base is None:
        return
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    counts = sorted({r["nodes"] for r in rows if r["formulation"] == formulation and r["kn"] == base})
    for n in counts:
        c = curve(rows, formulation, n, base)
        d = [r["delta"] for r in c]
        line, = ax.plot(d, [r["P"] for r in c], marker="o", ms=2.5,
                        label="N = %d" % round(c[0]["nodes_actual"]))
        if any(r["P_max"] > r["P_min"] for r in c):
            ax.fill_between(d, [r["P_min"] for r in c], [r["P_max"] for r in c],
                            color=line.get_color(), alpha=0.15)
    c = curve(rows, formulation, counts[-1], base)
    if converges(rows, formulation):
        ax.plot([r["delta"] for r in c], [r["P_exact"] for r in c], "k--",
                label="continuum closed form")
    finish(ax, "%s, k = %.3g %s: P–δ per node count" % (formulation, base, unit(rows, formulation)))
    save(fig, out_dir, name)


def plot_by_stiffness(rows, formulation, out_dir, name):
    sel = [r for r in rows if r["formulation"] == formulation]
    ks = defaultdict(set)
    for r in sel:
        ks[r["nodes"]].add(r["kn"])
    if not ks:
        return
    n = max(ks, key=lambda k: (len(ks[k]), k))
    if len(ks[n]) < 2:
        return
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    for i, k in enumerate(sorted(ks[n])):
        c = curve(rows, formulation, n, k)
        ax.plot([r["delta"] for r in c], [r["P"] for r in c], marker="o", ms=2.5,
                label="k = %.3g" % k)
        if converges(rows, formulation):
            ax.plot([r["delta"] for r in c], [r["P_exact"] for r in c], "k--", lw=0.8,
                    label="continuum closed form" if i == 0 else None)
    title = "%s, N = %d: P–δ per stiffness (%s)" % (formulation, round(c[0]["nodes_actual"]),
                                                   unit(rows, formulation))
    if converges(rows, formulation):
        title += "; dashed: closed form"
    finish(ax, title)
    save(fig, out_dir, name)


def plot_convergence(rows, out_dir):
    """Left: P(δ_max) against N for each formulation (log-log), the adapted closed form as a
    line. Right: each formulation's P(δ_max) over the adapted continuum value."""
    dmax = max(r["delta"] for r in rows)
    fig, (left, right) = plt.subplots(1, 2, figsize=(10.5, 4.2))
    reference = None
    for formulation in sorted({r["formulation"] for r in rows}):
        base = base_stiffness(rows, formulation)
        sel = sorted((r for r in rows if r["formulation"] == formulation and r["kn"] == base
                      and abs(r["delta"] - dmax) <= 1e-9 * dmax), key=lambda r: r["nodes_actual"])
        if not sel:
            continue
        n = [r["nodes_actual"] for r in sel]
        left.errorbar(n, [r["P"] for r in sel],
                      yerr=[[r["P"] - r["P_min"] for r in sel], [r["P_max"] - r["P"] for r in sel]],
                      marker="o", capsize=3, label="%s (k = %.3g %s)" % (formulation, base,
                                                                        unit(rows, formulation)))
        if formulation == "original":
            left.plot(n, [r["P_exact"] for r in sel], "k:", lw=1,
                      label="original, uniform nodes: kn* = kn·N/(4πR²)")
        if formulation == "adapted":
            reference = sel[0]["P_exact"]
            left.axhline(reference, color="k", ls="--", lw=1,
                         label="adapted continuum closed form (%.4g N)" % reference)
            right.plot(n, [r["P"] / r["P_exact"] for r in sel], marker="o", label="adapted / closed form")
            right.fill_between(n, [r["P_min"] / r["P_exact"] for r in sel],
                               [r["P_max"] / r["P_exact"] for r in sel], alpha=0.2)
    left.set_xscale("log")
    left.set_yscale("log")
    left.set_xlabel("surface nodes per sphere N")
    left.set_ylabel("P(δ = %.3g mm) [N]" % dmax)
    left.set_title("force at δ_max: original grows ∝ N, adapted converges", fontsize=9)
    left.grid(alpha=0.3, which="both")
    left.legend(fontsize=7)
    if reference is not None:
        right.axhline(1.0, color="k", ls="--", lw=1)
        right.set_xscale("log")
        right.set_xlabel("surface nodes per sphere N")
        right.set_ylabel("P(δ_max) / closed form")
        right.set_title("adapted formulation against the continuum closed form", fontsize=9)
        right.grid(alpha=0.3, which="both")
        right.legend(fontsize=7)
    else:
        right.axis("off")
    save(fig, out_dir, "cube27_convergence.png")


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    rows = read_numbers(sys.argv[1], text=("formulation", "kn_unit"), whole=("nodes", "converges"))
    if not rows:
        print("cube27.py: no rows in", sys.argv[1], file=sys.stderr)
        return 1
    out_dir = sys.argv[2]
    for formulation, tag in (("original", "fig4b"), ("adapted", "fig4d"),
                             ("single-node", "single_node"), ("volume", "volume")):
        plot_by_nodes(rows, formulation, out_dir, "cube27_%s_%s_by_nodes.png" % (tag, formulation))
    for formulation, tag in (("original", "fig4c"), ("adapted", "fig4e"),
                             ("single-node", "single_node"), ("volume", "volume")):
        plot_by_stiffness(rows, formulation, out_dir,
                          "cube27_%s_%s_by_stiffness.png" % (tag, formulation))
    plot_convergence(rows, out_dir)
    return 0


if __name__ == "__main__":
    sys.exit(main())
