#!/usr/bin/python3
"""Figures of lsdem-study verify, in the style of the papers their cases come from (Chung & Ooi,
Granular Matter 13, 2011): force against time and overlap, rebound against restitution,
tangential restitution and spin against the incident angle, beta against x, slide to roll,
free rotation, the errors against the node count, and the silo's discharge against Beverloo's
law (Beverloo, Leniger & van de Velde 1961: W^(2/5) against D).

usage: verify.py OUT_DIR   (reads OUT_DIR/verify_*.csv, writes OUT_DIR/verify_*.png)
Each PNG is written to a temporary name and renamed, so a failed run leaves no half image.
"""
import glob
import os
import sys

from plotting import plt, read_numbers, save

LAWS = ("adapted", "original", "volume", "single-node")
COLOURS = {"adapted": "C0", "original": "C1", "volume": "C2", "single-node": "C3"}


def series(out_dir, name):
    path = os.path.join(out_dir, "verify_%s.csv" % name)
    return read_numbers(path, text=()) if os.path.exists(path) else None


def normal_impacts(out_dir, kind, title):
    fig, (ax_t, ax_d) = plt.subplots(1, 2, figsize=(10, 4))
    drawn = False
    for law in LAWS:
        rows = series(out_dir, "normal_%s_%s" % (kind, law))
        ref = series(out_dir, "normal_%s_%s_reference" % (kind, law))
        if not rows:
            continue
        drawn = True
        c = COLOURS[law]
        ax_t.plot([1e6 * r["time"] for r in rows], [r["force"] for r in rows], c, lw=1.2,
                  label="lsdem, " + law)
        ax_d.plot([1e3 * r["overlap"] for r in rows], [r["force"] for r in rows], c, lw=1.2,
                  label="lsdem, " + law)
        if ref:
            ax_t.plot([1e6 * r["time"] for r in ref], [r["force"] for r in ref], c + "--", lw=0.9,
                      label="continuum, " + law)
            ax_d.plot([1e3 * r["overlap"] for r in ref], [r["force"] for r in ref], c + "--",
                      lw=0.9)
    if not drawn:
        plt.close(fig)
        return
    ax_t.set_xlabel("time in contact [µs]")
    ax_t.set_ylabel("normal force [N]")
    ax_d.set_xlabel("overlap [µm]")
    ax_d.set_ylabel("normal force [N]")
    ax_t.legend(fontsize=7)
    fig.suptitle(title)
    save(fig, out_dir, "verify_normal_%s.png" % kind)


def restitution(out_dir):
    fig, ax = plt.subplots(figsize=(5, 4.5))
    ax.plot([0, 1], [0, 1], "k-", lw=0.8, label="the input")
    drawn = False
    for law in LAWS:
        rows = series(out_dir, "restitution_" + law)
        if rows:
            drawn = True
            ax.plot([r["restitution"] for r in rows], [r["rebound_ratio"] for r in rows], "o",
                    color=COLOURS[law], ms=4, label=law)
    if not drawn:
        plt.close(fig)
        return
    ax.set_xlabel("restitution given")
    ax.set_ylabel("rebound / impact speed")
    ax.set_title("Chung & Ooi 3: a ball on a wall")
    ax.legend(fontsize=8)
    save(fig, out_dir, "verify_restitution.png")


def oblique_wall(out_dir):
    fig, (ax_e, ax_w) = plt.subplots(1, 2, figsize=(10, 4))
    drawn = False
    for law in ("adapted", "original"):
        rows = series(out_dir, "oblique_wall_" + law)
        if not rows:
            continue
        c = COLOURS[law]
        angle = [r["angle_deg"] for r in rows]
        ax_e.plot(angle, [r["et"] for r in rows], "o", color=c, ms=4, label="lsdem, " + law)
        ax_w.plot(angle, [r["spin"] for r in rows], "o", color=c, ms=4, label="lsdem, " + law)
        if not drawn:
            ax_e.plot(angle, [r["et_rigid"] for r in rows], "k-", lw=0.8, label="rigid body")
            ax_w.plot(angle, [r["spin_rigid"] for r in rows], "k-", lw=0.8, label="rigid body")
        if law == "adapted":
            ax_e.plot(angle, [r["et_continuum"] for r in rows], "--", color=c, lw=0.9,
                      label="adapted, continuum")
            ax_w.plot(angle, [r["spin_continuum"] for r in rows], "--", color=c, lw=0.9,
                      label="adapted, continuum")
        drawn = True
    if not drawn:
        plt.close(fig)
        return
    for ax in (ax_e, ax_w):
        ax.set_xlabel("incident angle from the normal [°]")
    ax_e.set_ylabel("tangential restitution v't / vt")
    ax_w.set_ylabel("rebound spin [rad/s]")
    ax_e.legend(fontsize=7)
    fig.suptitle("Chung & Ooi 4: 3.9 m/s at 5° … 85°, μ 0.092, e 0.98")
    save(fig, out_dir, "verify_oblique_wall.png")


def oblique_normal_speed(out_dir):
    fig, (ax_a, ax_w) = plt.subplots(1, 2, figsize=(10, 4))
    drawn = False
    for law in ("adapted", "original"):
        rows = series(out_dir, "oblique_normal_speed_" + law)
        if not rows:
            continue
        c = COLOURS[law]
        psi = [r["psi1"] for r in rows]
        ax_a.plot(psi, [r["psi2"] for r in rows], "o", color=c, ms=4, label="lsdem, " + law)
        ax_w.plot(psi, [r["spin"] for r in rows], "o", color=c, ms=4, label="lsdem, " + law)
        if not drawn:
            ax_a.plot(psi, [r["psi2_rigid"] for r in rows], "k-", lw=0.8, label="rigid body")
            ax_w.plot(psi, [r["spin_rigid"] for r in rows], "k-", lw=0.8, label="rigid body")
        if law == "adapted":
            ax_a.plot(psi, [r["psi2_continuum"] for r in rows], "--", color=c, lw=0.9,
                      label="adapted, continuum")
            ax_w.plot(psi, [r["spin_continuum"] for r in rows], "--", color=c, lw=0.9)
        drawn = True
    if not drawn:
        plt.close(fig)
        return
    for ax in (ax_a, ax_w):
        ax.set_xlabel("Ψ1 = Vt / (μ·Vn)")
    ax_a.set_ylabel("Ψ2 = V'ct / (μ·V'n)")
    ax_w.set_ylabel("R·ω' / (μ·Vn)")
    ax_a.legend(fontsize=7)
    fig.suptitle("Chung & Ooi 5: normal speed 5 m/s, μ 0.3, e 1")
    save(fig, out_dir, "verify_oblique_normal_speed.png")


def spin_impacts(out_dir, name, title):
    fig, (ax_b, ax_t) = plt.subplots(1, 2, figsize=(10, 4))
    drawn = False
    for law in ("adapted", "original"):
        rows = series(out_dir, "%s_%s" % (name, law))
        if not rows:
            continue
        c = COLOURS[law]
        x = [r["x"] for r in rows]
        ax_b.semilogx(x, [r["beta"] for r in rows], "o", color=c, ms=4, label="lsdem, " + law)
        ax_t.plot([r["tan_incident"] for r in rows], [r["tan_rebound"] for r in rows], "o",
                  color=c, ms=4, label="lsdem, " + law)
        if not drawn:
            ax_b.semilogx(x, [r["beta_rigid"] for r in rows], "k-", lw=0.8, label="rigid body")
            ax_t.plot([r["tan_incident"] for r in rows], [r["tan_rebound_rigid"] for r in rows],
                      "k-", lw=0.8, label="rigid body")
        if law == "adapted":
            ax_b.semilogx(x, [r["beta_continuum"] for r in rows], "--", color=c, lw=0.9,
                          label="adapted, continuum")
        drawn = True
    if not drawn:
        plt.close(fig)
        return
    ax_b.set_xlabel("x = 3.5·μ·(1+e)·Vcn / Vct")
    ax_b.set_ylabel("β = −V'ct / Vct")
    ax_t.set_xlabel("tan of the incident angle, Vct / Vcn")
    ax_t.set_ylabel("tan of the rebound angle, V'ct / V'cn")
    ax_b.legend(fontsize=7)
    fig.suptitle(title)
    save(fig, out_dir, "verify_%s.png" % name)


def spin_pair(out_dir):
    fig, ax = plt.subplots(figsize=(5, 4.5))
    drawn = False
    for law in ("adapted", "original"):
        rows = series(out_dir, "spin_pair_" + law)
        if not rows:
            continue
        w = [r["spin"] for r in rows]
        if not drawn:
            ax.plot(w, w, "k-", lw=0.8, label="rigid body: ω' = ω")
        ax.plot(w, [r["spin_after"] for r in rows], "o", color=COLOURS[law], ms=4,
                label="lsdem, " + law)
        drawn = True
    if not drawn:
        plt.close(fig)
        return
    ax.set_xlabel("spin before [rad/s]")
    ax.set_ylabel("spin after [rad/s]")
    ax.set_title("Chung & Ooi 7: two balls spinning oppositely")
    ax.legend(fontsize=8)
    save(fig, out_dir, "verify_spin_pair.png")


def slide_to_roll(out_dir):
    paths = sorted(glob.glob(os.path.join(out_dir, "verify_slide_to_roll_*.csv")))
    if not paths:
        return
    fig, (ax_v, ax_z) = plt.subplots(1, 2, figsize=(10, 4))
    for path in paths:
        label = os.path.basename(path)[len("verify_slide_to_roll_"):-len(".csv")]
        rows = read_numbers(path, text=())
        ax_v.plot([r["time"] for r in rows], [r["speed"] for r in rows], lw=0.9, label=label)
        ax_z.plot([r["time"] for r in rows], [1e3 * r["rise"] for r in rows], lw=0.6, label=label)
    ax_v.axhline(5.0 / 7.0 * 1000.0, color="k", lw=0.8, ls="--", label="5/7·v₀")
    ax_v.set_xlabel("time [s]")
    ax_v.set_ylabel("speed of the centre [mm/s]")
    ax_z.set_xlabel("time [s]")
    ax_z.set_ylabel("height of the centre − R [µm]")
    ax_v.legend(fontsize=6)
    fig.suptitle("A ball thrown flat on a floor: slides, then rolls (law_e<restitution>_n<nodes>)")
    save(fig, out_dir, "verify_slide_to_roll.png")


def free_rotation(out_dir):
    rows = series(out_dir, "free_rotation")
    if not rows:
        return
    fig, ax = plt.subplots(figsize=(6, 4))
    t = [r["time"] for r in rows]
    for k, label in ((1, "ω₁"), (2, "ω₂ (intermediate axis)"), (3, "ω₃")):
        ax.plot(t, [r["omega%d" % k] for r in rows], lw=1, label=label)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("spin in the body's frame [rad/s]")
    ax.set_title("A box spun about its intermediate axis")
    ax.legend(fontsize=8)
    save(fig, out_dir, "verify_free_rotation.png")


def convergence(out_dir):
    rows = series(out_dir, "convergence")
    if not rows:
        return
    quantities = [k for k in rows[0] if k not in ("nodes",)]
    fig, ax = plt.subplots(figsize=(6, 4.5))
    n = [r["nodes"] for r in rows]
    for q in quantities:
        ax.loglog(n, [max(abs(r[q]), 1e-6) for r in rows], "o-", ms=4, lw=1, label=q)
    ax.set_xlabel("nodes of the ball")
    ax.set_ylabel("|error| (relative), adapted")
    ax.set_title("Convergence with the node count")
    ax.legend(fontsize=7)
    save(fig, out_dir, "verify_convergence.png")


def silo(out_dir):
    kinds = [k for k in ("spheres", "sand") if series(out_dir, "silo_" + k)]
    if not kinds:
        return
    fig, (flow, mass) = plt.subplots(1, 2, figsize=(11, 4.5))
    for n, kind in enumerate(kinds):
        rows = series(out_dir, "silo_" + kind)
        d = [r["orifice"] for r in rows]
        w = [r["mass_flow"] ** 0.4 for r in rows]
        flow.plot(d, w, "o", color="C%d" % n, label=kind)
        if len(rows) >= 2:
            # The least-squares line of W^(2/5) on D (the fit the study judges), to its root k·d.
            mean_d, mean_w = sum(d) / len(d), sum(w) / len(w)
            slope = sum((a - mean_d) * (b - mean_w) for a, b in zip(d, w)) / \
                sum((a - mean_d) ** 2 for a in d)
            root = mean_d - mean_w / slope
            rho, size = rows[0]["bulk_density"], rows[0]["grain_size"]
            c = slope ** 2.5 / (rho * 9810.0 ** 0.5)
            xs = [root, max(d)]
            flow.plot(xs, [slope * (x - root) for x in xs], "-", lw=1, color="C%d" % n,
                      label="Beverloo: C = %.2f, k = %.2f" % (c, root / size))
        curves = series(out_dir, "silo_%s_discharge" % kind) or []
        for m, orifice in enumerate(sorted({r["orifice"] for r in curves})):
            pts = [r for r in curves if r["orifice"] == orifice]
            mass.plot([r["time"] for r in pts], [1e9 * r["mass"] for r in pts],
                      ("-" if n == 0 else "--"), lw=1, color="C%d" % m,
                      label="%s, D = %g mm" % (kind, orifice))
    flow.set_xlabel("orifice diameter D [mm]")
    flow.set_ylabel("W^(2/5)  [(t/s)^(2/5)]")
    flow.set_xlim(left=0)
    flow.set_ylim(bottom=0)
    flow.set_title("Mass flow against Beverloo's law")
    flow.legend(fontsize=8)
    mass.set_xlabel("time since the orifice opened [s]")
    mass.set_ylabel("mass out [mg]")
    mass.set_title("Discharge")
    mass.legend(fontsize=7)
    save(fig, out_dir, "verify_silo.png")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out_dir = sys.argv[1]
    normal_impacts(out_dir, "wall", "Chung & Ooi 2: a ball's normal impact on a wall, 3.9 m/s")
    normal_impacts(out_dir, "pair", "Chung & Ooi 1: two balls meet head on, 3.9 m/s")
    restitution(out_dir)
    oblique_wall(out_dir)
    oblique_normal_speed(out_dir)
    spin_impacts(out_dir, "spin_wall", "Chung & Ooi 6: a spinning ball on a wall, μ 0.4, e 0.5")
    spin_impacts(out_dir, "spin_heavy_ball",
                 "Chung & Ooi 8: a spinning ball on a heavy ball 5R, μ 0.4, e 0.5")
    spin_pair(out_dir)
    slide_to_roll(out_dir)
    free_rotation(out_dir)
    convergence(out_dir)
    silo(out_dir)


if __name__ == "__main__":
    main()
