#!/usr/bin/python3
"""Acoustic emission of a run (ae_events.csv, history.csv, summary.json): three PNGs.

  <prefix>_activity.png  axial stress and cumulative events against axial strain, and the
                         events per time window against time (their clustering in time)
  <prefix>_map.png       events in space, coloured by time, sized by magnitude
  <prefix>_bvalue.png    magnitude-frequency distribution N(>= M) with the b-value of
                         summary.json (Aki's maximum likelihood above the completeness
                         magnitude, with its standard error)

Usage: postproc/plot_ae.py RESULTS_DIR [-o PREFIX] [--windows N]
Needs Debian's /usr/bin/python3 with numpy and matplotlib.
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from csvdata import read_columns, require  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("results")
    p.add_argument("-o", "--prefix", default=None, help="default: RESULTS_DIR/ae")
    p.add_argument("--windows", type=int, default=100, help="time windows of the rate panel")
    a = p.parse_args()
    prefix = a.prefix or os.path.join(a.results, "ae")
    ev = read_columns(os.path.join(a.results, "ae_events.csv"), text_columns=("type",))
    require(ev, "ae_events.csv", ["time", "x", "y", "energy", "magnitude", "cracks", "type"])
    hist = read_columns(os.path.join(a.results, "history.csv"))
    with open(os.path.join(a.results, "summary.json")) as f:
        ae = json.load(f).get("acoustic_emission", {})
    t = ev["time"]
    if len(t) == 0:
        sys.exit("no events in %s" % a.results)

    # Activity: stress and cumulative events against strain (strain at each event's time).
    strain = np.interp(t, hist["time"], hist["axial_strain"])
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(7, 7))
    ax.plot(hist["axial_strain"] * 100, hist["axial_stress"] / 1e6, "k-", lw=1)
    ax.set_xlabel("axial strain (%)")
    ax.set_ylabel("axial stress (MPa)")
    axc = ax.twinx()
    axc.plot(strain * 100, np.arange(1, len(t) + 1), "C3-", lw=1)
    axc.set_ylabel("cumulative AE events", color="C3")
    ax.set_title("%d events from %d cracks" % (len(t), int(ev["cracks"].sum())), fontsize=9)
    edges = np.linspace(0, max(hist["time"].max(), t.max()), a.windows + 1)
    counts, _ = np.histogram(t, bins=edges)
    width = edges[1] - edges[0]
    ax2.bar(edges[:-1] * 1e3, counts, width=width * 1e3, align="edge", color="C0")
    ax2.set_xlabel("time (ms)")
    ax2.set_ylabel("events per %.3g ms" % (width * 1e3))
    cv = counts.std() / counts.mean() if counts.mean() > 0 else float("nan")
    ax2.set_title("events per time window (coefficient of variation %.2f)" % cv, fontsize=9)
    fig.tight_layout()
    fig.savefig(prefix + "_activity.png", dpi=130)

    # Map: events in space, coloured by time, sized by magnitude.
    fig, ax = plt.subplots(figsize=(5.6, 9))
    m = ev["magnitude"]
    finite = np.isfinite(m)
    size = 4 + 30 * (m - m[finite].min()) / max(np.ptp(m[finite]), 1e-12)
    sc = ax.scatter(ev["x"][finite] * 1e3, ev["y"][finite] * 1e3, c=t[finite] * 1e3,
                    s=size[finite], cmap="viridis", edgecolors="none")
    fig.colorbar(sc, ax=ax, label="time (ms)")
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title("AE events (size: magnitude)", fontsize=9)
    fig.tight_layout()
    fig.savefig(prefix + "_map.png", dpi=130)

    # Magnitude-frequency with the summary's b-value.
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ms = np.sort(m[finite])
    ax.semilogy(ms, len(ms) - np.arange(len(ms)), "k.", ms=3, label="N(>= M)")
    b, err, mc = ae.get("b_value"), ae.get("b_value_error"), ae.get("completeness_magnitude")
    if b is not None and mc is not None:
        n_mc = ae.get("events_above_completeness", 0)
        mm = np.linspace(mc, ms.max(), 50)
        ax.semilogy(mm, n_mc * 10 ** (-b * (mm - mc)), "C3-",
                    label="b = %.2f +- %.2f above Mc = %.1f (Aki)" % (b, err, mc))
        ax.axvline(mc, color="C3", ls=":", lw=1)
    ax.set_xlabel("magnitude M = 2/3 log10(E / J) - 3.2")
    ax.set_ylabel("events with magnitude >= M")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(prefix + "_bvalue.png", dpi=130)
    print("%s_{activity,map,bvalue}.png: %d events, b = %s" % (prefix, len(t), b))


if __name__ == "__main__":
    main()
