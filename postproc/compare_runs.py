#!/usr/bin/python3
"""Compares two or more vorodec runs of the same specimen: axial stress against axial strain, and
each run's crack map (cracks.csv: red tensile, blue shear) with its crack counts and lengths and the fraction
of cracks within 30 degrees of the (vertical) load axis.

Usage: postproc/compare_runs.py RUN_DIR RUN_DIR... [--labels A B...] -o out.png

Needs Debian's /usr/bin/python3 with python3-numpy and python3-matplotlib.
"""
import argparse
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

from csvdata import read_columns, require  # noqa: E402


def crack_segments(c):
    a = np.radians(c["orientation_deg"])
    half = 0.5 * c["length"][:, None] * np.stack([np.cos(a), np.sin(a)], axis=1)
    centre = np.stack([c["x"], c["y"]], axis=1)
    return np.stack([centre - half, centre + half], axis=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--labels", nargs="+")
    ap.add_argument("-o", "--output", required=True)
    args = ap.parse_args()
    labels = args.labels or [os.path.basename(os.path.normpath(r)) for r in args.runs]
    if len(labels) != len(args.runs):
        ap.error("give one label per run")
    n = len(args.runs)
    fig, axes = plt.subplots(1, n + 1, figsize=(4.2 * (n + 1), 5.2),
                             gridspec_kw={"width_ratios": [1.6] + [1] * n})
    for k, (run, label) in enumerate(zip(args.runs, labels)):
        h = read_columns(os.path.join(run, "history.csv"))
        require(h, run, ["axial_strain", "axial_stress"])
        with open(os.path.join(run, "summary.json")) as f:
            s = json.load(f)
        axes[0].plot(1e3 * h["axial_strain"], h["axial_stress"] / 1e6,
                     label="%s: UCS %.1f MPa, E %.1f GPa" % (
                         label, s["peak_stress_Pa"] / 1e6, s["youngs_modulus_Pa"] / 1e9))
        c = read_columns(os.path.join(run, "cracks.csv"), text_columns=("type",))
        tensile = np.array([t == "tensile" for t in c["type"]], dtype=bool)
        ax = axes[k + 1]
        seg = crack_segments(c) if len(tensile) else np.zeros((0, 2, 2))
        for mask, colour in ((tensile, "tab:red"), (~tensile, "tab:blue")):
            ax.add_collection(LineCollection(1e3 * seg[mask], colors=colour, linewidths=0.8))
        o = c["orientation_deg"] % 180.0
        near = np.mean((o >= 60) & (o <= 120)) if len(o) else float("nan")
        length = c["length"] * 1e3
        ax.set_title("%s\n%d tensile (%.0f mm), %d shear (%.0f mm)\n%.0f %% within 30 deg of the "
                     "axis" % (label, tensile.sum(), length[tensile].sum(), (~tensile).sum(),
                               length[~tensile].sum(), 100 * near), fontsize=9)
        ax.set_aspect("equal")
        ax.autoscale()
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
    axes[0].set_xlabel("axial strain (1e-3)")
    axes[0].set_ylabel("axial stress (MPa)")
    axes[0].legend(fontsize=8)
    axes[0].grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.output, dpi=130)
    print(args.output)


if __name__ == "__main__":
    main()
