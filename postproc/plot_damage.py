#!/usr/bin/python3
"""Plots the damage measures of a vorodec history CSV against the stress ratio and the strain.

Usage: postproc/plot_damage.py results/ucs_marble/history.csv [-o out.png]

Left: contact failure rate D_Mi and damage density D_Ma against the stress ratio (axial stress /
peak axial stress) on the loading branch up to the peak, as in Fig. 8 of the marble paper
("Mesomechanical characteristics of rock failure under variable amplitude cyclic loading by DEM",
Rock Mechanics and Rock Engineering); each has its own axis, so the small pre-peak D_Ma shows.
Right: both against axial strain through the post-peak branch, each on its own axis, with the
stress-strain curve on a third (the marble paper's Fig. 6 a-b), so the four stages (elastic,
stable crack growth, accelerating crack growth, post-peak) can be read off. In a cyclic run the
unloading and reloading branches are drawn as well: the damage stays flat along them.
Needs the columns axial_strain, axial_stress, failure_rate and damage_density.
Default output: <csv folder>/damage.png.

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

COLUMNS = ("axial_strain", "axial_stress", "failure_rate", "damage_density")


def plot(d, title, out):
    keep = np.all([np.isfinite(d[c]) for c in COLUMNS], axis=0)
    strain, stress = d["axial_strain"][keep], d["axial_stress"][keep]
    dmi, dma = d["failure_rate"][keep], d["damage_density"][keep]
    if len(stress) == 0 or np.max(stress) <= 0:
        raise ValueError("no positive axial stress in the history")
    ipeak = int(np.argmax(stress))
    peak = stress[ipeak]
    ratio = stress / peak

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5), dpi=150)
    ax2 = ax.twinx()
    pre = slice(0, ipeak + 1)
    ax.plot(ratio[pre], dmi[pre], color="tab:red", lw=1.6, label="contact failure rate $D_{Mi}$")
    ax2.plot(ratio[pre], dma[pre], color="tab:blue", lw=1.6, label="damage density $D_{Ma}$")
    ax.axvline(0.8, color="0.6", lw=0.8, ls=":")
    ax.set_xlabel("stress ratio $\\sigma_1 / \\sigma_{peak}$ (loading branch to the peak)")
    ax.set_ylabel("contact failure rate $D_{Mi}$", color="tab:red")
    ax2.set_ylabel("damage density $D_{Ma}$", color="tab:blue")
    ax.set_xlim(0, 1.02)
    ax.set_ylim(bottom=0)
    ax2.set_ylim(bottom=0)
    lines = ax.get_lines()[:1] + ax2.get_lines()[:1]
    ax.legend(lines, [l.get_label() for l in lines], loc="upper left", fontsize=8)
    ax.set_title("damage vs stress ratio (peak %.2f MPa)" % (peak / 1e6))

    bx2, bx3 = bx.twinx(), bx.twinx()
    bx3.spines["right"].set_position(("axes", 1.14))
    bx.plot(strain * 100, dmi, color="tab:red", lw=1.6, label="$D_{Mi}$")
    bx2.plot(strain * 100, dma, color="tab:blue", lw=1.6, label="$D_{Ma}$")
    bx3.plot(strain * 100, stress / 1e6, color="black", lw=1.2, label="axial stress")
    bx.axvline(strain[ipeak] * 100, color="0.6", lw=0.8, ls=":")
    bx.set_xlabel("axial strain (%)")
    bx.set_ylabel("$D_{Mi}$", color="tab:red")
    bx2.set_ylabel("$D_{Ma}$", color="tab:blue")
    bx3.set_ylabel("axial stress (MPa)")
    for axis in (bx, bx2, bx3):
        axis.set_ylim(bottom=0)
    lines = bx.get_lines()[:1] + bx2.get_lines()[:1] + bx3.get_lines()[:1]
    bx.legend(lines, [l.get_label() for l in lines], loc="upper left", fontsize=8)
    bx.set_title("damage and stress vs axial strain")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
    return peak, dmi[ipeak], dma[ipeak], dmi[-1], dma[-1]


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("history", help="history.csv of a run")
    p.add_argument("-o", "--output", help="PNG to write (default: <csv folder>/damage.png)")
    args = p.parse_args(argv)
    folder = os.path.dirname(os.path.abspath(args.history))
    out = args.output or os.path.join(folder, "damage.png")
    try:
        d = read_columns(args.history)
        require(d, args.history, COLUMNS)
        peak, dmi_p, dma_p, dmi_e, dma_e = plot(d, os.path.basename(folder), out)
    except (OSError, ValueError) as e:
        print("plot_damage: %s" % e, file=sys.stderr)
        return 1
    print("plot_damage: wrote %s (peak %.4g MPa; at peak D_Mi %.4g, D_Ma %.4g; at end D_Mi %.4g, "
          "D_Ma %.4g)" % (out, peak / 1e6, dmi_p, dma_p, dmi_e, dma_e))
    return 0


if __name__ == "__main__":
    sys.exit(main())
