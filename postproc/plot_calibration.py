#!/usr/bin/python3
"""Plots what `vorodec calibrate` wrote in its results folder:

  calibration_history.png   objective and worst target (in tolerances) against evaluations
  calibration_targets.png   each target (mean over the seeds, +- their standard deviation)
                            against the runs used, with the wanted value and its tolerance band
  calibration_sensitivity.png  heat map of d ln(target) / d ln(parameter), the last round
  calibration_micro_macro.png  one panel per parameter: the target it moves most, at each
                            sensitivity round's base and moved point (the micro-macro relation)

Usage: postproc/plot_calibration.py results/calibrate_marble [-o folder]

Needs Debian's /usr/bin/python3 with python3-numpy and python3-matplotlib.
"""
import argparse
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.ticker import NullFormatter  # noqa: E402

PHASE_COLOURS = {"start": "k", "dimensional": "tab:purple", "sensitivity": "tab:grey",
                 "linearised": "tab:orange", "optimiser": "tab:blue", "rescaled": "tab:green"}


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def unit(quantity):
    """Scale and unit label of a quantity for plotting."""
    if quantity.endswith("youngs_modulus_Pa"):
        return 1e-9, "GPa"
    if quantity.endswith("_Pa"):
        return 1e-6, "MPa"
    if quantity == "friction_angle_deg":
        return 1.0, "deg"
    return 1.0, ""


def plot_history(history, out):
    ev = np.array([int(r["evaluation"]) for r in history])
    obj = np.array([float(r["objective"]) for r in history])
    worst = np.array([float(r["worst"]) for r in history])
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for phase, colour in PHASE_COLOURS.items():
        m = np.array([r["phase"] == phase for r in history])
        if m.any():
            ax.semilogy(ev[m], obj[m], "o", color=colour, label=phase)
            ax.semilogy(ev[m], worst[m], "x", color=colour)
    # history.csv names each evaluation's best so far (older ones did not: the lowest objective).
    if "best" in history[0]:
        best = np.array([int(r["best"]) - 1 for r in history])
    else:
        best = np.array([int(np.argmin(obj[: i + 1])) for i in range(len(obj))])
    ax.semilogy(ev, obj[best], "-", color="tab:green", label="best set's objective")
    ax.axhline(1.0, color="tab:red", lw=0.8, ls="--", label="worst target = its tolerance")
    ax.set_xlabel("evaluation")
    ax.set_ylabel("objective (o), worst |error| / tolerance (x)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    plt.close(fig)


def plot_targets(history, targets, out):
    runs = np.array([int(r["runs"]) for r in history])
    n = len(targets)
    cols = min(n, 3)
    fig, axes = plt.subplots((n + cols - 1) // cols, cols, figsize=(4.2 * cols, 3.2 * ((n + cols - 1) // cols)),
                             squeeze=False)
    for k, t in enumerate(targets):
        ax = axes[k // cols][k % cols]
        scale, label = unit(t["quantity"])
        mean = np.array([float(r[t["target"] + "_mean"]) for r in history]) * scale
        sd = np.array([float(r[t["target"] + "_sd"]) for r in history]) * scale
        value = float(t["value"]) * scale
        tol = float(t["tolerance"]) * (scale if t["absolute"] == "1" else abs(value))
        ax.axhspan(value - tol, value + tol, color="tab:green", alpha=0.2, label="wanted +- tolerance")
        ax.axhline(value, color="tab:green")
        ax.errorbar(runs, mean, yerr=sd, fmt="o", ms=3, color="tab:blue", label="mean +- sd over seeds")
        ax.set_title("%s (%s)" % (t["target"], t["quantity"]), fontsize=9)
        ax.set_xlabel("runs used")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        if k == 0:
            ax.legend(fontsize=7)
    for k in range(n, axes.size):
        axes[k // cols][k % cols].axis("off")
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    plt.close(fig)


def last_round(sens):
    r = max(int(s["round"]) for s in sens)
    return [s for s in sens if int(s["round"]) == r], r


def plot_heat_map(sens, out):
    last, r = last_round(sens)
    targets = list(dict.fromkeys(s["target"] for s in last))
    params = list(dict.fromkeys(s["parameter"] for s in last))
    m = np.zeros((len(targets), len(params)))
    for s in last:
        m[targets.index(s["target"]), params.index(s["parameter"])] = float(s["elasticity"])
    fig, ax = plt.subplots(figsize=(2.8 + 1.1 * len(params), 1.8 + 0.5 * len(targets)))
    lim = max(1e-9, np.nanmax(np.abs(m)))
    # Cells as wide as their labels need: square cells left most of a wide figure empty.
    im = ax.imshow(m, cmap="RdBu_r", vmin=-lim, vmax=lim, aspect="auto")
    for i in range(len(targets)):
        for j in range(len(params)):
            ax.text(j, i, "%+.2f" % m[i, j], ha="center", va="center", fontsize=8)
    ax.set_xticks(range(len(params)), params, rotation=30, ha="right", fontsize=8)
    ax.set_yticks(range(len(targets)), targets, fontsize=8)
    ax.set_title("d ln(target) / d ln(parameter), round %d (base evaluation %s)"
                 % (r, last[0]["base_evaluation"]), fontsize=9)
    fig.colorbar(im, ax=ax, shrink=0.8)
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    plt.close(fig)


def plot_micro_macro(sens, targets, out):
    params = list(dict.fromkeys(s["parameter"] for s in sens))
    last, _ = last_round(sens)
    scale_of = {t["target"]: unit(t["quantity"]) for t in targets}
    cols = min(4, len(params))
    nrows = (len(params) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(3.9 * cols, 4.3 * nrows), squeeze=False)
    for ax in axes.flat[len(params):]:
        ax.set_visible(False)
    for j, p in enumerate(params):
        ax = axes[j // cols][j % cols]
        mine = [s for s in last if s["parameter"] == p]
        # The target this parameter moves most (a failed moved set's nan elasticity never wins).
        target = max(mine, key=lambda s: np.nan_to_num(abs(float(s["elasticity"])), nan=-1.0))["target"]
        scale, label = scale_of[target]
        xs, ys = [], []
        for s in sens:
            if s["parameter"] != p or s["target"] != target:
                continue
            x = [float(s["parameter_base"]), float(s["parameter_moved"])]
            y = [float(s["target_base"]) * scale, float(s["target_moved"]) * scale]
            xs += x
            ys += y
            ax.loglog(x, y, "o-", label="round %s, from %.3g: slope %+.2f (log-log)"
                      % (s["round"], x[0], float(s["elasticity"])))
        # Three labelled ticks across the points: a short decade has no major tick, and its nine
        # minor labels overlap.
        ticks = np.geomspace(min(xs), max(xs), 3)
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_xticks(ticks, ["%.3g" % t for t in ticks], fontsize=7)
        ticks = np.geomspace(min(ys), max(ys), 3)
        ax.yaxis.set_minor_formatter(NullFormatter())
        ax.set_yticks(ticks, ["%.3g" % t for t in ticks], fontsize=7)
        ax.set_xlabel(p, fontsize=8)
        ax.set_ylabel("%s (%s)" % (target, label))
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.18))
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder", help="results folder of vorodec calibrate")
    ap.add_argument("-o", "--out", help="folder for the PNGs (default: the results folder)")
    a = ap.parse_args()
    out = a.out or a.folder
    os.makedirs(out, exist_ok=True)
    history = rows(os.path.join(a.folder, "history.csv"))
    targets = rows(os.path.join(a.folder, "targets.csv"))
    plot_history(history, os.path.join(out, "calibration_history.png"))
    plot_targets(history, targets, os.path.join(out, "calibration_targets.png"))
    written = ["calibration_history.png", "calibration_targets.png"]
    sens_path = os.path.join(a.folder, "sensitivity.csv")
    if os.path.exists(sens_path) and rows(sens_path):
        sens = rows(sens_path)
        plot_heat_map(sens, os.path.join(out, "calibration_sensitivity.png"))
        plot_micro_macro(sens, targets, os.path.join(out, "calibration_micro_macro.png"))
        written += ["calibration_sensitivity.png", "calibration_micro_macro.png"]
    print("wrote %s in %s" % (", ".join(written), out))


if __name__ == "__main__":
    main()
