#!/usr/bin/python3
"""Plots and fits the creep stages of a vorodec run: axial strain against time in days per stage,
the macro Burger's model fitted to each stage, the paper's fits overlaid, and crack counts.

Usage: postproc/plot_creep.py results/creep/history.csv --confining 25e6
           [--zero-stage hydrostatic] [--paper 160:27.9,9613,1220,119 ...] [-o out.png]
           [--csv fits.csv]

A creep stage is a run of history rows with one stage label that spans more than --min-span
seconds of simulated time (default an hour; ramps last seconds). Each is fitted with the 1D Burger's model of [Guo2020],
eq. 17, in the stage's own time t (days from its first row):
    eps(t) = s/E1 + s t/eta1 + s/E2 (1 - exp(-E2 t/eta2)),   s = mean axial stress - confining,
by linear least squares in (1/E1, 1/eta1, 1/E2) for each retardation time eta2/E2 of a log grid.
--paper S:E1,eta1,E2,eta2 (GPa and GPa d) draws the paper's fit at deviatoric stress S (MPa) over
the stage whose stress is nearest. Prints one line per stage: S, E1, eta1, E2, eta2, the fit's
RMS residual, and the strain at the stage's end (simulated and the paper's curve).
--zero-stage NAME takes the axial strain from the end of that stage (a laboratory zeroes its gauges
after the hydrostatic stage, before the deviatoric load).

Needs Debian's /usr/bin/python3 with python3-numpy and python3-matplotlib.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from csvdata import read_columns, require  # noqa: E402

DAY = 86400.0


def creep_stages(data, min_span):
    """(label, row indices) of each stage spanning more than min_span seconds."""
    stages, start = [], 0
    labels = [label.split(":")[0] for label in data["stage"]]  # with its :start and :end rows
    for i in range(1, len(labels) + 1):
        if i == len(labels) or labels[i] != labels[start]:
            rows = np.arange(start, i)
            if data["time"][rows[-1]] - data["time"][rows[0]] > min_span:
                stages.append((labels[start], rows))
            start = i
    return stages


def strain_at_stage_end(data, stage):
    """Axial strain at the last row marking the end of `stage`, or None if no row does."""
    ends = np.flatnonzero(np.asarray(data["stage"]) == stage + ":end")
    return float(data["axial_strain"][ends[-1]]) if ends.size else None


def burgers(s, t, e1, eta1, e2, eta2):
    """Strain of the macro Burger's model; s in Pa, t in days, moduli in Pa, viscosities Pa d."""
    return s / e1 + s * t / eta1 + s / e2 * (1.0 - np.exp(-e2 * t / eta2))


def fit(s, t, eps):
    """Least-squares E1, eta1, E2, eta2 (Pa, Pa d) and RMS residual; preferring fits whose
    compliances are all positive (a term the data do not show gets an infinite modulus)."""
    best = None
    for tau in np.logspace(-5, 1, 600):  # days
        a = np.column_stack([np.full_like(t, s), s * t, s * (1.0 - np.exp(-t / tau))])
        coef, *_ = np.linalg.lstsq(a, eps, rcond=None)
        rms = float(np.sqrt(np.mean((a @ coef - eps) ** 2)))
        key = (bool(np.any(coef <= 0)), rms)
        if best is None or key < best[0]:
            inv = [1.0 / c if c > 0 else float("inf") for c in coef]
            best = (key, (inv[0], inv[1], inv[2], inv[2] * tau, rms))
    return best[1]


def parse_paper(items):
    out = []
    for item in items or []:
        s, rest = item.split(":")
        e1, eta1, e2, eta2 = (float(v) for v in rest.split(","))
        out.append((float(s) * 1e6, e1 * 1e9, eta1 * 1e9, e2 * 1e9, eta2 * 1e9))
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("history")
    p.add_argument("--confining", type=float, default=0.0, help="Pa, lateral stress")
    p.add_argument("--paper", action="append", help="S:E1,eta1,E2,eta2 (MPa; GPa, GPa d)")
    p.add_argument("--min-span", type=float, default=3600.0, help="s, shortest creep stage")
    p.add_argument("--zero-stage", help="take the axial strain from this stage's end")
    p.add_argument("-o", "--output")
    p.add_argument("--csv", help="write the fits here")
    args = p.parse_args()
    data = read_columns(args.history)
    require(data, args.history, ("time", "axial_strain", "axial_stress", "cracks_tensile",
                                 "cracks_shear"))
    if args.zero_stage:
        zero = strain_at_stage_end(data, args.zero_stage)
        if zero is None:
            sys.exit("%s: no row marks the end of stage '%s'" % (args.history, args.zero_stage))
        data["axial_strain"] = data["axial_strain"] - zero
    stages = creep_stages(data, args.min_span)
    if not stages:
        sys.exit("%s: no stage spans more than %g s of simulated time" % (args.history,
                                                                        args.min_span))
    paper = parse_paper(args.paper)
    fig, (ax, axc) = plt.subplots(2, 1, figsize=(8, 8), sharex=True,
                                  gridspec_kw={"height_ratios": [3, 1]})
    lines = ["stage,deviatoric_MPa,E1_GPa,eta1_GPa_d,E2_GPa,eta2_GPa_d,rms_strain,"
             "end_strain,paper_end_strain"]
    for name, rows in stages:
        t_abs = data["time"][rows] / DAY
        t = t_abs - t_abs[0]
        eps = data["axial_strain"][rows]
        s = float(np.mean(data["axial_stress"][rows])) - args.confining
        e1, eta1, e2, eta2, rms = fit(s, t, eps)
        ax.plot(t_abs, eps * 1e3, ".", ms=2, label="%s (vorodec)" % name)
        ax.plot(t_abs, burgers(s, t, e1, eta1, e2, eta2) * 1e3, "-", lw=1,
                label="%s fit: E1 %.1f GPa, eta1 %.3g GPa d, E2 %.3g GPa, eta2 %.3g GPa d"
                % (name, e1 / 1e9, eta1 / 1e9, e2 / 1e9, eta2 / 1e9))
        paper_end = float("nan")
        if paper:
            ps = min(paper, key=lambda q: abs(q[0] - s))
            curve = burgers(ps[0], t, *ps[1:])
            paper_end = float(curve[-1])
            ax.plot(t_abs, curve * 1e3, "--", lw=1,
                    label="%s paper's fit at %.0f MPa (Table 3)" % (name, ps[0] / 1e6))
        lines.append("%s,%.6g,%.6g,%.6g,%.6g,%.6g,%.3g,%.6g,%.6g" % (
            name, s / 1e6, e1 / 1e9, eta1 / 1e9, e2 / 1e9, eta2 / 1e9, rms, eps[-1], paper_end))
    ax.set_ylabel("axial strain (1e-3)" + (", from the end of stage '%s'" % args.zero_stage
                                            if args.zero_stage else ""))
    ax.legend(fontsize=6, loc="best")
    ax.set_title(os.path.basename(os.path.dirname(os.path.abspath(args.history))))
    days = data["time"] / DAY
    axc.plot(days, data["cracks_tensile"], label="tensile")
    axc.plot(days, data["cracks_shear"], label="shear")
    axc.set_xlabel("time (days)")
    axc.set_ylabel("cracks")
    axc.legend(fontsize=7)
    fig.tight_layout()
    out = args.output or os.path.splitext(args.history)[0] + "_creep.png"
    fig.savefig(out, dpi=130)
    print("\n".join(lines))
    if args.csv:
        with open(args.csv, "w") as f:
            f.write("\n".join(lines) + "\n")
    print("plot written to %s" % out)


if __name__ == "__main__":
    main()
