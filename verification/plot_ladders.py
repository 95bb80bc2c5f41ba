#!/usr/bin/python3
"""Plots verification/ladders.csv (written by verification/run.sh) as cost-accuracy panels: one
log-log panel per ladder, error against wall time, one point per setting (labelled with it), the
default ringed, the reference named, and the observed order in the setting only where the
errors fall monotonically as the setting is refined ("no trend" otherwise). Wall times below
1 ms are drawn at 1 ms.
Usage: /usr/bin/python3 plot_ladders.py ladders.csv ladders.png"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FLOOR = 1e-3  # s


def observed_order(pts):
    """Least-squares slope of log(error) against log(setting) if the errors fall strictly from
    the coarsest setting to the finest (every ladder here is finer at a smaller setting)."""
    rungs = sorted((p for p in pts if p[1] > 0), key=lambda p: -p[0])
    if len(rungs) < 2 or any(b[1] >= a[1] for a, b in zip(rungs, rungs[1:])):
        return None
    x = [math.log(p[0]) for p in rungs]
    y = [math.log(p[1]) for p in rungs]
    mx, my = sum(x) / len(x), sum(y) / len(y)
    return sum((a - mx) * (b - my) for a, b in zip(x, y)) / sum((a - mx) ** 2 for a in x)


def main(src, dst):
    ladders = {}
    with open(src, newline="") as f:
        for row in csv.DictReader(f):
            ladders.setdefault(row["ladder"], []).append(row)
    n = len(ladders)
    cols = 2
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(11, 3.9 * rows), squeeze=False)
    for ax, (name, rungs) in zip(axes.flat, ladders.items()):
        pts = [(float(r["parameter"]), float(r["error"]), float(r["seconds"]), r["default"] == "1")
               for r in rungs]
        shown = [p for p in pts if p[1] > 0]
        ax.loglog([max(p[2], FLOOR) for p in shown], [p[1] for p in shown], "o-", color="C0")
        for x, e, s, d in shown:
            ax.annotate("%g" % x, (max(s, FLOOR), e), textcoords="offset points", xytext=(4, 4),
                        fontsize=7)
            if d:
                ax.loglog([max(s, FLOOR)], [e], "o", ms=13, mfc="none", mec="C3", mew=2,
                          label="default")
        if any(p[3] and p[1] == 0 for p in pts):
            ax.plot([], [], " ", label="the default is the reference")
        order = observed_order(pts)
        order_text = "%.2f" % order if order is not None else "no trend (errors not monotone)"
        ax.set_title("%s\nreference: %s\nobserved order in the setting: %s"
                     % (name, rungs[0]["reference"], order_text), fontsize=8)
        ax.set_xlabel("wall time (s); points: %s" % rungs[0]["parameter_name"], fontsize=7)
        ax.set_ylabel("relative error", fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(dst, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
