#!/usr/bin/python3
"""Plots verification/ladders.csv (written by verification/run.sh): one log-log panel per
ladder, error against the discretisation parameter, the default setting ringed, the observed
order in the title and each rung's wall time beside it.
Usage: /usr/bin/python3 plot_ladders.py ladders.csv ladders.png"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(src, dst):
    ladders = {}
    with open(src, newline="") as f:
        for row in csv.DictReader(f):
            ladders.setdefault(row["ladder"], []).append(row)
    n = len(ladders)
    cols = 2
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(11, 3.6 * rows), squeeze=False)
    for ax, (name, rungs) in zip(axes.flat, ladders.items()):
        pts = [(float(r["parameter"]), float(r["error"]), float(r["seconds"]), r["default"] == "1")
               for r in rungs]
        fit = [p for p in pts if p[1] > 0]
        ax.loglog([p[0] for p in fit], [p[1] for p in fit], "o-", color="C0")
        for x, e, s, d in fit:
            ax.annotate(f"{s:.1f} s", (x, e), textcoords="offset points", xytext=(4, 4),
                        fontsize=7)
            if d:
                ax.loglog([x], [e], "o", ms=13, mfc="none", mec="C3", mew=2, label="default")
        defaults = [p for p in pts if p[3] and p[1] == 0]
        for x, _, _, _ in defaults:  # the default is the converged reference itself
            ax.axvline(x, color="C3", ls="--", label="default (reference)")
        ax.set_title(f"{name}\norder {float(rungs[0]['order']):.2f}", fontsize=9)
        ax.set_xlabel(rungs[0]["parameter_name"], fontsize=8)
        ax.set_ylabel("relative error", fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(dst, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
