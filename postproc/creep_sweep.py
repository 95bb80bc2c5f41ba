#!/usr/bin/python3
"""Micro-macro relations of Burger's contacts from `vorodec batch models/batch_creep_sweep.toml`:
fits the macro Burger's model to the creep stage of every case and relates each swept contact
parameter to the macro parameter it drives ([Guo2020], Fig. 5: Kmn -> E1, Cmn -> eta1,
Kkn -> E2, Ckn -> eta2), and the friction angle to all four.

Usage: postproc/creep_sweep.py results/batch_creep_sweep [--confining 25e6] [-o sweep.png]

Cases are read by folder name: base, <param>_x0.5, <param>_x2 (param kmn, cmn, kkn, ckn) and
friction_<deg>. For each parameter it prints the macro values at x0.5, x1, x2, the log-log slope
(1: proportional) and the R^2 of a straight line through the three points (linear, as the paper
reports, if close to 1). Needs Debian's /usr/bin/python3 with numpy and matplotlib.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from csvdata import read_columns  # noqa: E402
from plot_creep import DAY, creep_stages, fit, strain_at_stage_end  # noqa: E402

MACRO = ("E1", "eta1", "E2", "eta2")
DRIVES = {"kmn": "E1", "cmn": "eta1", "kkn": "E2", "ckn": "eta2"}


def case_fit(folder, confining):
    data = read_columns(os.path.join(folder, "history.csv"))
    stages = creep_stages(data, 3600.0)
    if not stages:
        raise ValueError("%s: no creep stage" % folder)
    _, rows = stages[-1]
    t = (data["time"][rows] - data["time"][rows[0]]) / DAY
    s = float(np.mean(data["axial_stress"][rows])) - confining
    # Strains from the end of the hydrostatic stage, if the run has one (as the paper counts).
    zero = strain_at_stage_end(data, "hydrostatic") or 0.0
    e1, eta1, e2, eta2, _ = fit(s, t, data["axial_strain"][rows] - zero)
    return dict(zip(MACRO, (e1, eta1, e2, eta2)))


def line_r2(x, y):
    a = np.polyfit(x, y, 1)
    res = y - np.polyval(a, x)
    tot = y - np.mean(y)
    return 1.0 - float(res @ res) / float(tot @ tot) if float(tot @ tot) > 0 else float("nan")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("folder")
    p.add_argument("--confining", type=float, default=25e6)
    p.add_argument("--base-friction", type=float, default=28.0,
                   help="deg, the base case's friction (models/triaxial_sandstone.toml)")
    p.add_argument("-o", "--output")
    args = p.parse_args()
    fits = {}
    for name in sorted(os.listdir(args.folder)):
        path = os.path.join(args.folder, name)
        if os.path.isfile(os.path.join(path, "history.csv")):
            try:
                fits[name] = case_fit(path, args.confining)
            except ValueError as e:
                print("skipped: %s" % e, file=sys.stderr)
    if "base" not in fits:
        sys.exit("%s: no base case" % args.folder)
    fig, axes = plt.subplots(1, 5, figsize=(20, 4))
    print("parameter,macro,x0.5,x1,x2,loglog_slope,line_R2")
    for ax, (param, macro) in zip(axes, DRIVES.items()):
        keys = ["%s_x0.5" % param, "base", "%s_x2" % param]
        if not all(k in fits for k in keys):
            continue
        x = np.array([0.5, 1.0, 2.0])
        y = np.array([fits[k][macro] for k in keys])
        slope = np.polyfit(np.log(x), np.log(y), 1)[0]
        print("%s,%s,%.4g,%.4g,%.4g,%.3f,%.4f" % (param, macro, y[0], y[1], y[2], slope,
                                                   line_r2(x, y)))
        ax.plot(x, y / y[1], "o-", label="%s (slope %.2f)" % (macro, slope))
        for other in MACRO:
            if other != macro:
                yo = np.array([fits[k][other] for k in keys])
                ax.plot(x, yo / yo[1], ".--", lw=0.8, label=other)
        ax.set_xlabel("%s / base" % param)
        ax.set_ylabel("macro / base")
        ax.legend(fontsize=7)
    fr = sorted((float(k.split("_")[1]), k) for k in fits if k.startswith("friction_"))
    if fr:
        ax = axes[4]
        xs = [f for f, _ in fr] + [args.base_friction]
        keys = [k for _, k in fr] + ["base"]
        order = np.argsort(xs)
        for macro in MACRO:
            ys = np.array([fits[keys[i]][macro] for i in order])
            ax.plot(np.array(xs)[order], ys / fits["base"][macro], "o-", label=macro)
            print("friction,%s,%s" % (macro, ",".join("%.4g" % v for v in ys)))
        ax.set_xlabel("friction (deg)")
        ax.set_ylabel("macro / base")
        ax.legend(fontsize=7)
    fig.tight_layout()
    out = args.output or os.path.join(args.folder, "creep_sweep.png")
    fig.savefig(out, dpi=110)
    print("plot written to %s" % out)


if __name__ == "__main__":
    main()
