#!/usr/bin/python3
"""Plots a cyclic run: the stress-strain curve with its cycles, and the per-cycle measures of
cycles.csv against the cycle number (secant modulus, generalized Poisson's ratio, dissipated work
per cycle and summed, residual strain), as Figs. 3b, 4b, 5b and 12-13 of the marble paper
("Mesomechanical characteristics of rock failure under variable amplitude cyclic loading by DEM",
Rock Mechanics and Rock Engineering). Stalled cycles (the specimen peaked below the target) are
drawn hollow.

Usage: postproc/plot_cycles.py results/cyclic_marble [-o out.png]
Default output: <results folder>/cycles.png.

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


def plot(folder, out):
    h = read_columns(os.path.join(folder, "history.csv"))
    c = read_columns(os.path.join(folder, "cycles.csv"))
    require(h, "history.csv", ("axial_strain", "axial_stress"))
    require(c, "cycles.csv", ("cycle", "secant_modulus_Pa", "poisson_ratio",
                              "dissipated_work_J_m3", "dissipated_total_J_m3", "residual_strain",
                              "stalled"))
    n = c["cycle"]
    full = c["stalled"] == 0
    fig, ax = plt.subplots(2, 3, figsize=(15, 8.5))
    a = ax[0, 0]
    a.plot(h["axial_strain"] * 100, h["axial_stress"] / 1e6, lw=0.8, color="k")
    a.set(xlabel="axial strain (%)", ylabel="axial stress (MPa)", title="stress-strain with cycles")
    panels = [
        (ax[0, 1], c["secant_modulus_Pa"] / 1e9, "secant modulus (GPa)"),
        (ax[0, 2], c["poisson_ratio"], "generalized Poisson's ratio"),
        (ax[1, 0], c["dissipated_work_J_m3"] / 1e3, "dissipated work per cycle (kJ/m³)"),
        (ax[1, 1], c["dissipated_total_J_m3"] / 1e3, "dissipated work, summed (kJ/m³)"),
        (ax[1, 2], c["residual_strain"] * 100, "residual axial strain (%)"),
    ]
    for a, y, label in panels:
        a.plot(n, y, "-", color="C0", lw=1)
        a.plot(n[full], y[full], "o", color="C0", label="cycle")
        if np.any(~full):
            a.plot(n[~full], y[~full], "o", mfc="none", color="C0", label="stalled cycle")
        a.set(xlabel="cycle", ylabel=label)
        a.set_xticks(n)
        a.grid(alpha=0.3)
    ax[0, 1].legend()
    fig.suptitle(os.path.basename(os.path.normpath(folder)))
    fig.tight_layout()
    fig.savefig(out, dpi=120)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("folder", help="results folder of a cyclic run (history.csv, cycles.csv)")
    p.add_argument("-o", "--output", help="PNG file (default: <folder>/cycles.png)")
    args = p.parse_args()
    out = args.output or os.path.join(args.folder, "cycles.png")
    try:
        plot(args.folder, out)
    except (OSError, ValueError) as e:
        print("plot_cycles: %s" % e, file=sys.stderr)
        return 1
    print("plot_cycles: wrote %s" % out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
