"""What the lsdem-study plot scripts share: headless matplotlib, CSV files with '#' comment
lines, and PNGs written to a temporary name and renamed, so a failed run leaves no half image.
"""
import csv
import os

import matplotlib

matplotlib.use("Agg")  # no display on a build machine
import matplotlib.pyplot as plt  # noqa: E402


def read_csv(path):
    """Rows of a CSV file as dicts of strings, skipping lines that start with '#'."""
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    return list(csv.DictReader(lines))


def read_numbers(path, text=("formulation",), whole=("nodes",)):
    """Rows of a CSV file with every column a float, except those named in text (kept as
    strings) and in whole (ints)."""
    def convert(key, value):
        if key in text:
            return value
        return int(value) if key in whole else float(value)
    return [{k: convert(k, v) for k, v in r.items()} for r in read_csv(path)]


def save(fig, out_dir, name):
    """Write fig as out_dir/name atomically and close it."""
    final = os.path.join(out_dir, name)
    tmp = os.path.join(out_dir, "." + name + ".tmp.png")
    fig.savefig(tmp, dpi=120, bbox_inches="tight")
    plt.close(fig)
    os.replace(tmp, final)
    print("wrote", final)
