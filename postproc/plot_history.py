#!/usr/bin/python3
"""Plots a vorodec history CSV: stress-strain curves with crack counts.

Usage: postproc/plot_history.py results/ucs_marble/history.csv [-o out.png]

Reads the CSV's header row and uses the columns it knows, ignoring any others:
  axial_strain, axial_stress            required (strain dimensionless, stress in Pa)
  lateral_strain, volumetric_strain     optional, drawn on the same axes
  cracks_tensile, cracks_shear          optional, drawn as counts on a second y-axis
Axial stress is drawn in MPa against axial strain (right-hand side) and against lateral and
volumetric strain; the curves are drawn compression-positive whatever sign convention the file
uses, so lateral (extensional) strain lands on the negative side, as in the usual rock-mechanics
plot. The title is the name of the CSV's folder. Default output: <csv without .csv>.png.

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

REQUIRED = ("axial_strain", "axial_stress")
OPTIONAL = ("time", "lateral_strain", "volumetric_strain", "cracks_tensile", "cracks_shear")


def read_history(path):
    """Returns {column: float array} for the known columns; NaN where a cell is not a number."""
    columns = read_columns(path)
    require(columns, path, REQUIRED)
    data = {n: columns[n] for n in REQUIRED + OPTIONAL if n in columns}
    # Rows without both axial strain and stress (e.g. a run killed mid-line) are dropped.
    keep = np.isfinite(data["axial_strain"]) & np.isfinite(data["axial_stress"])
    data = {k: v[keep] for k, v in data.items()}
    if len(data["axial_strain"]) == 0:
        raise ValueError("%s has no data rows with axial_strain and axial_stress" % path)
    return data


def sign_at_max_abs(a):
    finite = np.isfinite(a)
    if not finite.any():
        return 1.0
    v = a[finite][np.argmax(np.abs(a[finite]))]
    return -1.0 if v < 0 else 1.0


def plot(data, title, out):
    stress_sign = sign_at_max_abs(data["axial_stress"])
    strain_sign = sign_at_max_abs(data["axial_strain"])
    stress = stress_sign * data["axial_stress"] / 1e6  # MPa, compression positive
    ea = strain_sign * data["axial_strain"]

    fig, ax = plt.subplots(figsize=(9, 5.6), dpi=150)
    ax.plot(ea, stress, color="black", lw=1.6, label="axial strain")
    if "lateral_strain" in data:
        ax.plot(strain_sign * data["lateral_strain"], stress, color="tab:green", lw=1.4,
                label="lateral strain")
    if "volumetric_strain" in data:
        ax.plot(strain_sign * data["volumetric_strain"], stress, color="tab:purple", lw=1.4,
                ls="--", label="volumetric strain")
    ax.axvline(0.0, color="0.6", lw=0.8)
    # Post-peak gauges on fragments can run off far; keep the axial curve readable.
    amax = np.nanmax(np.abs(ea)) if np.isfinite(ea).any() else 0.0
    if amax > 0:
        ax.set_xlim(-1.5 * amax, 1.1 * amax)
    ax.set_xlabel("strain (-), compression positive")
    ax.set_ylabel("axial stress (MPa)")
    ax.grid(True, lw=0.4, alpha=0.5)

    if np.isfinite(stress).any():
        k = int(np.nanargmax(stress))
        ax.plot([ea[k]], [stress[k]], "o", color="tab:red", ms=5, zorder=5)
        lo, hi = np.nanmin(ea), np.nanmax(ea)
        right_half = hi > lo and ea[k] > 0.5 * (lo + hi)
        ax.annotate("peak %.4g MPa\nat %.3g" % (stress[k], ea[k]), (ea[k], stress[k]),
                    textcoords="offset points", xytext=(-8 if right_half else 8, -28),
                    ha="right" if right_half else "left", fontsize=8,
                    bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="none", alpha=0.85))

    handles, labels = ax.get_legend_handles_labels()
    crack_cols = [c for c in ("cracks_tensile", "cracks_shear") if c in data]
    if crack_cols:
        ax2 = ax.twinx()
        colours = {"cracks_tensile": "tab:red", "cracks_shear": "tab:blue"}
        for c in crack_cols:
            ax2.step(ea, data[c], where="post", color=colours[c], lw=1.0, alpha=0.8,
                     label=c.replace("cracks_", "") + " cracks")
        ax2.set_ylabel("number of cracks")
        ax2.set_ylim(bottom=0)
        h2, l2 = ax2.get_legend_handles_labels()
        handles, labels = handles + h2, labels + l2
    ax.legend(handles, labels, loc="upper left", fontsize=8, framealpha=0.9)
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("csv", help="vorodec history CSV, e.g. results/ucs_marble/history.csv")
    p.add_argument("-o", "--output", help="PNG to write (default: next to the CSV)")
    args = p.parse_args(argv)
    out = args.output or os.path.splitext(args.csv)[0] + ".png"
    title = os.path.basename(os.path.dirname(os.path.abspath(args.csv))) or args.csv
    try:
        data = read_history(args.csv)
        plot(data, title, out)
    except (OSError, ValueError) as e:
        print("plot_history: %s" % e, file=sys.stderr)
        return 1
    print("plot_history: wrote %s (%d rows)" % (out, len(data["axial_strain"])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
