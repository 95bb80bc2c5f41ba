#!/usr/bin/python3
"""Cracks before and after the peak of one run: type, orientation and localisation.

Prints the markdown rows of a verification table and draws <out>.png: the cracks before the peak
and after it (red tensile, blue shear, each drawn as its segment from cracks.csv) beside the
stress-strain curve with the peak marked. Used for B6's confined low-damping test
(verification/REPORT.md, "B6"): [Hazzard2000] section 4.2 describes the cracks at 20 MPa
confinement as mostly tensile and subvertical, sparse and scattered before the peak and clustered
along a macrofracture after it.

Measures (each for the cracks before the peak, after it, and all):
- tensile share: tensile cracks / all cracks (counts, as the paper counts bond breaks);
- subvertical share: cracks within 30 deg of the load axis (orientation 60-120 deg);
- localisation: the fraction of the specimen's area, in square cells of --cell m, that holds half
  of the cracks (the fewest cells, fullest first); a uniform scatter gives about 0.5 of the area
  the cracks reach, a single band a few per cent.

Usage: postproc/crack_evolution.py RUN_DIR [-o out] [--cell 0.01] [--label "alpha 0.015"]
Needs Debian's /usr/bin/python3 with numpy and matplotlib.
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from csvdata import read_columns  # noqa: E402


def half_area(x, y, cell, width, height):
    """Fraction of the width x height specimen's cells that hold half of the cracks at (x, y)."""
    if len(x) == 0:
        return float("nan")
    nx, ny = max(1, int(round(width / cell))), max(1, int(round(height / cell)))
    counts, _, _ = np.histogram2d(x, y, bins=(nx, ny),
                                  range=((x.min(), x.min() + width), (y.min(), y.min() + height)))
    full = np.sort(counts.ravel())[::-1]
    cells = np.searchsorted(np.cumsum(full), 0.5 * len(x)) + 1
    return cells / (nx * ny)


def measures(c, pick, cell, width, height):
    tensile = np.array([t == "tensile" for t in c["type"]])[pick]
    o = c["orientation_deg"][pick]
    n = int(pick.sum())
    return {
        "n": n,
        "tensile": tensile.mean() if n else float("nan"),
        "subvertical": ((o >= 60) & (o <= 120)).mean() if n else float("nan"),
        "half_area": half_area(c["x"][pick], c["y"][pick], cell, width, height),
    }


def draw(ax, c, pick, title, bounds):
    for kind, colour in (("tensile", "red"), ("shear", "blue")):
        sel = pick & np.array([t == kind for t in c["type"]])
        a = np.radians(c["orientation_deg"][sel])
        half = 0.5 * c["length"][sel]
        x, y = c["x"][sel], c["y"][sel]
        segs = np.stack([np.stack([x - half * np.cos(a), y - half * np.sin(a)], 1),
                         np.stack([x + half * np.cos(a), y + half * np.sin(a)], 1)], 1)
        ax.add_collection(LineCollection(segs, colors=colour, linewidths=0.6,
                                         label="%s (%d)" % (kind, sel.sum())))
    ax.set_aspect("equal")
    ax.set_xlim(bounds[0], bounds[1])
    ax.set_ylim(bounds[2], bounds[3])
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, loc="lower right")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("run")
    p.add_argument("-o", "--out", default=None)
    p.add_argument("--cell", type=float, default=0.01, help="m, the localisation cell")
    p.add_argument("--label", default="", help="the run's name in the table and figure")
    a = p.parse_args()
    with open(os.path.join(a.run, "summary.json")) as f:
        s = json.load(f)
    h = read_columns(os.path.join(a.run, "history.csv"), text_columns=("stage",))
    c = read_columns(os.path.join(a.run, "cracks.csv"), text_columns=("type",))
    peak = int(np.argmax(h["axial_stress"]))
    t_peak = h["time"][peak]
    width = c["x"].max() - c["x"].min()
    height = c["y"].max() - c["y"].min()
    before = c["time"] <= t_peak
    rows = [("before the peak", before), ("after the peak", ~before),
            ("all", np.ones_like(before))]
    m = [measures(c, pick, a.cell, width, height) for _, pick in rows]
    print("| %s: cracks | tensile share | within 30 deg of the load axis | "
          "area holding half the cracks |" % (a.label or os.path.basename(a.run.rstrip("/"))))
    print("|---|---|---|---|")
    for (name, _), x in zip(rows, m):
        print("| %s: %d | %.2f | %.2f | %.3f |" % (name, x["n"], x["tensile"], x["subvertical"],
                                                 x["half_area"]))
    print("peak %.1f MPa at axial strain %.3f %% (row %d of %d); status: %s" % (
        h["axial_stress"][peak] / 1e6, 100 * h["axial_strain"][peak], peak, len(h["time"]),
        s["status"]))

    fig, (curve, pre, post) = plt.subplots(1, 3, figsize=(12, 5.5),
                                           gridspec_kw={"width_ratios": [1.3, 1, 1]})
    curve.plot(100 * h["axial_strain"], h["axial_stress"] / 1e6, "k")
    curve.plot(100 * h["axial_strain"][peak], h["axial_stress"][peak] / 1e6, "o", color="C1",
               label="peak %.0f MPa" % (h["axial_stress"][peak] / 1e6))
    curve.set(xlabel="axial strain (%)", ylabel="axial stress (MPa)")
    curve.legend(fontsize=8)
    bounds = (c["x"].min(), c["x"].max(), c["y"].min(), c["y"].max())
    draw(pre, c, before, "cracks before the peak", bounds)
    draw(post, c, ~before, "cracks after the peak", bounds)
    fig.suptitle(a.label or a.run, fontsize=10)
    fig.tight_layout()
    out = a.out or os.path.join(a.run, "crack_evolution")
    fig.savefig(out + ".png", dpi=130)
    print("figure:", out + ".png")


if __name__ == "__main__":
    main()
