#!/usr/bin/python3
"""Cost-accuracy plot of one ladder: error against wall time (log-log), one point per setting,
the default ringed, each point labelled with its setting, the observed order in the title.
Usage: /usr/bin/python3 plot_cost_accuracy.py ladder.csv out.png "title"
(ladder.csv: parameter,value,error,seconds,default,order; written by vorodec_verify.)"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FormatStrFormatter  # noqa: E402


def main(src, dst, title):
    with open(src, newline="") as f:
        rows = list(csv.DictReader(f))
    pts = [(float(r["seconds"]), float(r["error"]), float(r["parameter"]), r["default"] == "1")
           for r in rows if float(r["error"]) > 0]
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", color="C0")
    for s, e, par, d in pts:
        if d:
            ax.plot([s], [e], "o", ms=14, mfc="none", mec="C3", label="default")
        ax.annotate("%g" % par, (s, e), textcoords="offset points", xytext=(6, 4), fontsize=8)
    order = float(rows[0]["order"]) if rows else float("nan")
    # Within a decade matplotlib labels the minor ticks in full scientific notation, which overlap.
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_formatter(FormatStrFormatter("%g"))
        axis.set_minor_formatter(FormatStrFormatter("%g"))
    ax.tick_params(axis="x", which="both", labelrotation=45, labelsize=7)
    ax.tick_params(axis="y", which="both", labelsize=7)
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("error")
    order_text = ("%.2f" % order) if order == order else "no trend (errors not monotone)"
    ax.set_title("%s\nobserved order in the setting: %s" % (title, order_text), fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(dst, dpi=130)


if __name__ == "__main__":
    main(*sys.argv[1:4])
