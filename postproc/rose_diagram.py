#!/usr/bin/python3
"""Draws rose ("plum blossom") diagrams of failed contacts from a vorodec rose.csv.

Usage: postproc/rose_diagram.py results/ucs_marble/rose.csv [-o out.png] [--max-panels N]

rose.csv has one row per VTK output time with P21 (failed contact length / specimen area, 1/m;
Eq. 4 of the marble paper, "Mesomechanical characteristics of rock failure under variable
amplitude cyclic loading by DEM", Rock Mechanics and Rock Engineering) in 18 bins of 10 degrees
of crack line orientation (0-180 degrees from the x axis), for all, tensile and shear cracks.
Each output time gets a polar panel with stacked bars (tensile red, shear blue), mirrored to
180-360 degrees since a crack line has no sense; 90 degrees (up) is a vertical crack, parallel to
the axial load. The panel title gives the stage, the time and the stress ratio (axial stress /
peak; the peak is taken from history.csv next to rose.csv when present); post-peak rows are
marked. A last panel overlays every output time's total as a closed curve, the form of the
marble paper's Fig. 7 ("plum blossom"). With more rows than --max-panels (default 8), evenly
spaced rows are drawn (always the last). Default output: <csv folder>/rose.png.

Needs Debian's /usr/bin/python3 with python3-numpy and python3-matplotlib.
"""
import argparse
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

from csvdata import read_columns, require  # noqa: E402

BINS = 18


def bin_columns(kind):
    return ["%s_%d_%d" % (kind, 10 * k, 10 * (k + 1)) for k in range(BINS)]


def peak_of(folder, rose):
    """(peak axial stress, time of the peak) from history.csv, else from the rose rows."""
    path = os.path.join(folder, "history.csv")
    if os.path.isfile(path):
        h = read_columns(path)
        if "axial_stress" in h and "time" in h and np.isfinite(h["axial_stress"]).any():
            i = int(np.nanargmax(h["axial_stress"]))
            return h["axial_stress"][i], h["time"][i]
    i = int(np.nanargmax(rose["axial_stress"]))
    return rose["axial_stress"][i], rose["time"][i]


def pick_rows(n, most):
    if n <= most:
        return list(range(n))
    return sorted(set(int(round(x)) for x in np.linspace(0, n - 1, most)))


def draw(path, out, most):
    d = read_columns(path)
    tensile_cols, shear_cols = bin_columns("tensile"), bin_columns("shear")
    require(d, path, ["time", "axial_stress"] + tensile_cols + shear_cols)
    n = len(d["time"])
    if n == 0:
        raise ValueError("%s has no rows" % path)
    folder = os.path.dirname(os.path.abspath(path))
    peak, t_peak = peak_of(folder, d)
    tensile = np.array([d[c] for c in tensile_cols]).T  # rows x bins
    shear = np.array([d[c] for c in shear_cols]).T
    stages = d.get("stage", [""] * n)

    rows = pick_rows(n, most)
    panels = len(rows) + 1
    ncol = min(panels, 3)
    nrow = math.ceil(panels / ncol)
    fig = plt.figure(figsize=(4.2 * ncol, 4.4 * nrow), dpi=150)
    width = np.radians(10.0)
    centres = np.radians(10.0 * np.arange(BINS) + 5.0)
    theta = np.concatenate([centres, centres + np.pi])
    short = []
    for p, i in enumerate(rows):
        ax = fig.add_subplot(nrow, ncol, p + 1, projection="polar")
        t2, s2 = np.tile(tensile[i], 2), np.tile(shear[i], 2)
        ax.bar(theta, t2, width=width, color="tab:red", edgecolor="white", lw=0.3, label="tensile")
        ax.bar(theta, s2, width=width, bottom=t2, color="tab:blue", edgecolor="white", lw=0.3,
               label="shear")
        ratio = d["axial_stress"][i] / peak if peak > 0 else math.nan
        post = d["time"][i] > t_peak
        state = "stress ratio %.2f%s" % (ratio, " (post-peak)" if post else "")
        short.append("%s, t = %.4g s, %s" % (stages[i], d["time"][i], state))
        ax.set_title("%s, t = %.4g s\n%s\nP21 = %.3g 1/m" % (
            stages[i], d["time"][i], state, tensile[i].sum() + shear[i].sum()), fontsize=8)
        ax.set_thetagrids(range(0, 360, 30))
        ax.set_ylim(0, 1.05 * (t2 + s2).max() or 1.0)  # an empty rose starts at 0 too
        ax.set_rlabel_position(0)  # along 0 degrees, where horizontal cracks are rare
        ax.yaxis.set_major_locator(MaxNLocator(4))
        ax.tick_params(labelsize=6)
        if p == 0:
            fig.legend(loc="upper left", fontsize=8)

    ax = fig.add_subplot(nrow, ncol, panels, projection="polar")
    closed = np.concatenate([theta[:BINS], theta[BINS:], theta[:1]])
    colours = plt.cm.viridis(np.linspace(0, 1, len(rows)))
    for colour, i, label in zip(colours, rows, short):
        total = tensile[i] + shear[i]
        r = np.concatenate([total, total, total[:1]])
        ax.plot(closed, r, color=colour, lw=1.2, label=label)
    ax.set_title("P21 per 10-degree bin (1/m), all output times", fontsize=8)
    ax.set_thetagrids(range(0, 360, 30))
    ax.set_rlabel_position(0)
    ax.yaxis.set_major_locator(MaxNLocator(4))
    ax.tick_params(labelsize=6)
    ax.legend(loc="upper left", bbox_to_anchor=(1.05, 1.0), fontsize=6)
    fig.suptitle("failed contacts by orientation: %s" % os.path.basename(folder))
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
    return rows, tensile[rows[-1]] + shear[rows[-1]]


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("rose", help="rose.csv of a run")
    p.add_argument("-o", "--output", help="PNG to write (default: <csv folder>/rose.png)")
    p.add_argument("--max-panels", type=int, default=8, help="most output times drawn")
    args = p.parse_args(argv)
    out = args.output or os.path.join(os.path.dirname(os.path.abspath(args.rose)), "rose.png")
    try:
        rows, last = draw(args.rose, out, max(1, args.max_panels))
    except (OSError, ValueError) as e:
        print("rose_diagram: %s" % e, file=sys.stderr)
        return 1
    share = last[7:11].sum() / last.sum() if last.sum() > 0 else 0.0
    print("rose_diagram: wrote %s (%d output times; last: P21 %.4g 1/m, %.0f %% of it at "
          "70-110 deg)" % (out, len(rows), last.sum(), 100 * share))
    return 0


if __name__ == "__main__":
    sys.exit(main())
