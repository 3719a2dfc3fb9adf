"""The shear band of a periodic triaxial run of lsdem-run (a scene with a periodic cell and
[output] micromechanics = true): each grain's D²min and rotation since the start, from one
ParaView frame, on two vertical slices through the cell's middle; and the cell's deviator
ratio q/p and volumetric strain against axial strain, from cell.csv.

    /usr/bin/python3 tools/plots/shear_band.py RUN_FOLDER [--frame K] [--out band.png]

Strains are from cell.csv's first row (a run restarted from a checkpoint older than cell.csv,
format 9, starts its rows at the restart). The frame is the last one unless --frame is given; a frame split over MPI ranks (a .pvtu and
its pieces) is read whole. Prints the cell's state at the frame and the band: a band in a
periodic cell must repeat with it, so it lies along a family of the cell's lattice planes
(h, k, l), the phase h·x/Lx + k·y/Ly + l·z/Lz (mod 1) constant along each. For every family with
|h|, |k| <= 2, 0 <= l <= 2, the grains are binned by phase (20 bins) and the family whose
bins' mean D²min peaks highest over the overall mean (the contrast) is the band; its
inclination from horizontal and its width at half the peak above the mean are printed, with
the contrast the same search finds when the values are shuffled among the grains (no band).
"""
import argparse
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plotting import plt, read_csv, save  # noqa: E402

TYPES = {"Float64": np.float64, "Float32": np.float32, "Int32": np.int32, "Int64": np.int64,
         "UInt8": np.uint8}


def read_vtu(path):
    """The point arrays of a .vtu that lsdem writes (appended raw data, UInt64 byte counts)."""
    with open(path, "rb") as f:
        data = f.read()
    start = data.index(b'<AppendedData encoding="raw">')
    block = data.index(b"_", start) + 1
    head = data[:start].decode("latin1")
    arrays = {}
    for m in re.finditer(r'<DataArray type="(\w+)" Name="(\w+)" NumberOfComponents="(\d+)" '
                         r'format="appended" offset="(\d+)"', head):
        kind, name, components, offset = m.group(1), m.group(2), int(m.group(3)), int(m.group(4))
        at = block + offset
        size = int(np.frombuffer(data, np.uint64, 1, at)[0])
        values = np.frombuffer(data, TYPES[kind], size // np.dtype(TYPES[kind]).itemsize, at + 8)
        arrays[name] = values.reshape(-1, components) if components > 1 else values
    return arrays


def grain_points(arrays):
    """A piece's surface points with the grain of each (the grain index is per triangle)."""
    offsets = arrays["offsets"].astype(np.int64)
    corners = np.diff(np.concatenate([[0], offsets]))
    grain = np.zeros(len(arrays["Points"]), np.int64)
    grain[arrays["connectivity"]] = np.repeat(arrays["grain"], corners)
    return {"Points": arrays["Points"], "grain": grain, "d2min": arrays.get("d2min"),
            "rotation": arrays.get("rotation")}


def read_frame(folder, k):
    """Frame k's grain surfaces: the .vtu, or the pieces a .pvtu lists, joined."""
    whole = os.path.join(folder, "frames_grains_%d.vtu" % k)
    if os.path.exists(whole):
        return grain_points(read_vtu(whole))
    with open(os.path.join(folder, "frames_grains_%d.pvtu" % k)) as f:
        pieces = re.findall(r'<Piece Source="([^"]+)"', f.read())
    parts = [grain_points(read_vtu(os.path.join(folder, p))) for p in pieces]
    if any(part["d2min"] is None for part in parts):
        return {"d2min": None}
    return {n: np.concatenate([part[n] for part in parts]) for n in parts[0]}


def last_frame(folder):
    ks = [int(m.group(1)) for name in os.listdir(folder)
          for m in [re.match(r"frames_grains_(\d+)\.p?vtu$", name)] if m]
    if not ks:
        sys.exit("shear_band.py: no frames_grains_<k>.vtu in %s (run with vtk_period > 0)" % folder)
    return max(ks)


def frame_time(folder, k):
    with open(os.path.join(folder, "frames.pvd")) as f:
        for m in re.finditer(r'timestep="([^"]+)"[^>]*file="frames_grains_(\d+)\.p?vtu"', f.read()):
            if int(m.group(2)) == k:
                return float(m.group(1))
    return float("nan")


def per_grain(frame):
    """Each grain's centre (the mean of its surface points), D²min and rotation."""
    grain = frame["grain"]
    ids, first, counts = np.unique(grain, return_index=True, return_counts=True)
    order = np.argsort(grain, kind="stable")
    sums = np.add.reduceat(frame["Points"][order], np.searchsorted(grain[order], ids), axis=0)
    centres = sums / counts[:, None]
    return ids, centres, frame["d2min"][first], frame["rotation"][first]


def lattice_band(centres, values, size, bins=20):
    """The cell's lattice-plane family along which values concentrate most: (contrast, (h, k,
    l), the bins' means)."""
    best = None
    for h in range(-2, 3):
        for k in range(-2, 3):
            for l in range(0, 3):
                if (h, k, l) == (0, 0, 0) or (l == 0 and (h < 0 or (h == 0 and k < 0))):
                    continue  # (each family once: (h, k, l) and its negative are one)
                phase = (h * centres[:, 0] / size[0] + k * centres[:, 1] / size[1]
                         + l * centres[:, 2] / size[2]) % 1.0
                b = np.minimum((phase * bins).astype(int), bins - 1)
                means = np.array([values[b == i].mean() if np.any(b == i) else 0.0
                                  for i in range(bins)])
                contrast = means.max() / values.mean()
                if best is None or contrast > best[0]:
                    best = (contrast, (h, k, l), means)
    return best


def describe_band(band, size, values):
    """Inclination from horizontal (degrees), spacing of the family and width at half height
    (length units)."""
    contrast, (h, k, l), means = band
    normal = np.array([h / size[0], k / size[1], l / size[2]])
    spacing = 1.0 / np.linalg.norm(normal)
    inclination = np.degrees(np.arccos(abs(normal[2]) / np.linalg.norm(normal)))
    # The bins at half height and above next to the peak's (the profile wraps round).
    half = values.mean() + 0.5 * (means.max() - values.mean())
    n, top = len(means), int(np.argmax(means))
    wide = 1
    for step in (1, -1):
        k = 1
        while wide < n and means[(top + step * k) % n] >= half:
            wide += 1
            k += 1
    width = spacing * wide / n
    return inclination, spacing, width


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", help="lsdem-run's output folder")
    parser.add_argument("--frame", type=int, help="the frame's index (default: the last)")
    parser.add_argument("--out", default=None, help="the PNG (default: RUN/shear_band.png)")
    a = parser.parse_args()
    k = a.frame if a.frame is not None else last_frame(a.run)
    t = frame_time(a.run, k)
    frame = read_frame(a.run, k)
    if frame["d2min"] is None:
        sys.exit("shear_band.py: the frames carry no D²min (set [output] micromechanics = true)")
    ids, centres, d2min, rotation = per_grain(frame)

    cell = [{key: float(v) for key, v in r.items()} for r in read_csv(os.path.join(a.run, "cell.csv"))]
    size0 = np.array([cell[0]["size_x"], cell[0]["size_y"], cell[0]["size_z"]])
    ea = np.array([1 - r["size_z"] / size0[2] for r in cell])
    ev = np.array([1 - r["size_x"] * r["size_y"] * r["size_z"] / size0.prod() for r in cell])
    sx, sy, sz = (np.array([r["stress_" + c] for r in cell]) for c in "xyz")
    p = (sx + sy + sz) / 3
    q = sz - (sx + sy) / 2
    near = int(np.argmin([abs(r["time"] - t) for r in cell]))
    size = np.array([cell[near]["size_x"], cell[near]["size_y"], cell[near]["size_z"]])

    top = np.sort(d2min)[::-1][: max(1, len(d2min) // 10)]
    share = top.sum() / d2min.sum() if d2min.sum() > 0 else float("nan")
    print("frame %d at t = %.6g: %d grains, axial strain %.4f, volumetric %.4f, q/p %.3f"
          % (k, t, len(ids), ea[near], ev[near], q[near] / p[near] if p[near] else float("nan")))
    print("D2min: median %.4g, 90th percentile %.4g, largest %.4g; the top tenth holds %.2f of the sum"
          % (np.median(d2min), np.percentile(d2min, 90), d2min.max(), share))
    for name, values in (("D2min", d2min), ("rotation", rotation)):
        band = lattice_band(centres, values, size)
        inclination, spacing, width = describe_band(band, size, values)
        shuffled = lattice_band(centres, np.random.default_rng(1).permutation(values), size)
        print("%s band: lattice planes (%d, %d, %d), contrast %.2f (shuffled: %.2f), inclined "
              "%.1f deg from horizontal, %.2f wide at half height (the planes %.2f apart)"
              % ((name,) + band[1] + (band[0], shuffled[0], inclination, width, spacing)))

    fig, axes = plt.subplots(2, 3, figsize=(15, 11), constrained_layout=True)
    thick = 0.12 * size[:2].min()  # a slice a few grains thick through the middle
    middle = centres.min(axis=0) + 0.5 * (centres.max(axis=0) - centres.min(axis=0))
    d2 = np.log10(np.maximum(d2min, 1e-12))
    lo, hi = np.percentile(d2, [5, 99.5])
    rmax = np.percentile(rotation, 99)
    panels = [(d2, "log10 D²min (mm²)", "viridis", lo, hi), (rotation, "rotation (rad)", "magma", 0, rmax)]
    for row, (values, label, cmap, vmin, vmax) in enumerate(panels):
        for column, (across, along) in enumerate(((1, 0), (0, 1))):
            ax = axes[row][column]
            inside = np.abs(centres[:, across] - middle[across]) < thick / 2
            s = ax.scatter(centres[inside, along], centres[inside, 2], c=values[inside], s=10,
                           cmap=cmap, vmin=vmin, vmax=vmax, linewidths=0)
            ax.set_aspect("equal")
            ax.set_xlabel("xyz"[along] + " (mm)")
            ax.set_ylabel("z (mm)")
            ax.set_title("%s, grains within %.1f mm of %s = %.1f"
                         % (label, thick / 2, "xyz"[across], middle[across]), fontsize=9)
            fig.colorbar(s, ax=ax, shrink=0.8)
    ax = axes[0][2]
    for name, values, colour in (("D²min", d2min, "tab:green"), ("rotation", rotation, "tab:purple")):
        band = lattice_band(centres, values, size)
        _, spacing, _ = describe_band(band, size, values)
        across = (np.arange(len(band[2])) + 0.5) / len(band[2]) * spacing
        ax.plot(across, band[2] / values.mean(), "o-", color=colour,
                label="%s, planes (%d, %d, %d)" % ((name,) + band[1]))
    ax.axhline(1.0, color="grey", lw=0.8)
    ax.set_xlabel("across the band's lattice planes (mm)")
    ax.set_ylabel("mean over the grains there / overall mean")
    ax.set_title("the band: grains binned across the planes it lies along", fontsize=9)
    ax.legend(fontsize=8)
    ax = axes[1][2]
    ax.plot(100 * ea, q / p, label="q/p")
    ax.set_xlabel("axial strain (%)")
    ax.set_ylabel("q/p")
    ax2 = ax.twinx()
    ax2.plot(100 * ea, 100 * ev, color="tab:red", label="volumetric strain")
    ax2.set_ylabel("volumetric strain (%, compression > 0)", color="tab:red")
    ax.axvline(100 * ea[near], color="grey", lw=0.8, ls="--")
    ax.set_title("the cell: q/p and volumetric strain", fontsize=9)
    fig.suptitle("%s, frame %d: axial strain %.1f %%, D²min and rotation since the start"
                 % (os.path.basename(os.path.abspath(a.run)), k, 100 * ea[near]))
    out = a.out or os.path.join(a.run, "shear_band.png")
    save(fig, os.path.dirname(os.path.abspath(out)), os.path.basename(out))


if __name__ == "__main__":
    main()
