#!/usr/bin/python3
"""The low-damping study (B6; [Hazzard2000]): two runs of the same
model, quasi-static damping and low damping, compared. Prints the markdown rows of
verification/REPORT.md's B6 section and draws <out>.png: stress-strain curves and cumulative
cracks against strain, and cracks per time window, of both runs.

Usage: postproc/low_damping_study.py QUASI_STATIC_DIR LOW_DAMPING_DIR [-o b6_low_damping]
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
from csvdata import read_columns  # noqa: E402


def load(d):
    with open(os.path.join(d, "summary.json")) as f:
        s = json.load(f)
    h = read_columns(os.path.join(d, "history.csv"))
    c = read_columns(os.path.join(d, "cracks.csv"), text_columns=("type",))
    e = read_columns(os.path.join(d, "ae_events.csv"), text_columns=("type",))
    return s, h, c, e


def measures(s, h, c, e):
    o = c["orientation_deg"]
    tensile = np.array([t == "tensile" for t in c["type"]])
    near_axis = (o >= 60) & (o <= 120)  # within 30 deg of the (vertical) load axis
    multi = e["cracks"] >= 2
    # Clustering in time: cracks per window (1 % of the run) before the peak.
    t_peak = h["time"][np.argmax(h["axial_stress"])]
    edges = np.linspace(0, t_peak, 101)
    counts, _ = np.histogram(c["time"], bins=edges)
    return {
        "ucs": s["peak_stress_Pa"] / 1e6,
        "E": s["youngs_modulus_Pa"] / 1e9,
        "cracks": len(o),
        "tensile": tensile.mean() if len(o) else float("nan"),
        "near_axis": near_axis.mean() if len(o) else float("nan"),
        "events": len(e["time"]),
        "multi": float(e["cracks"][multi].sum()) / max(len(o), 1),
        "largest": float(e["cracks"].max()) if len(e["time"]) else 0,
        "b": (s.get("acoustic_emission") or {}).get("b_value"),
        "b_err": (s.get("acoustic_emission") or {}).get("b_value_error"),
        "cv": counts.std() / counts.mean() if counts.mean() > 0 else float("nan"),
        "wall": s["wall_time_s"],
        "steps": s["steps"],
        "blocks": s["blocks"],
    }


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("quasi_static")
    p.add_argument("low_damping")
    p.add_argument("-o", "--out", default="b6_low_damping")
    a = p.parse_args()
    runs = [load(a.quasi_static), load(a.low_damping)]
    m = [measures(*r) for r in runs]
    drop = 1 - m[1]["ucs"] / m[0]["ucs"]
    print("| measure | alpha 0.7 | alpha 0.015 | [Hazzard2000] |")
    print("|---|---|---|---|")
    print("| UCS (MPa) | %.1f | %.1f | 213 (quasi-static) |" % (m[0]["ucs"], m[1]["ucs"]))
    print("| strength drop at low damping | | %.1f %% | ~15 %% (LdB granite) |" % (100 * drop))
    print("| Young's modulus (GPa) | %.1f | %.1f | ~65 |" % (m[0]["E"], m[1]["E"]))
    print("| cracks | %d | %d | - |" % (m[0]["cracks"], m[1]["cracks"]))
    print("| tensile share of cracks | %.2f | %.2f | mostly tensile |" % (m[0]["tensile"], m[1]["tensile"]))
    print("| share within 30 deg of the load axis | %.2f | %.2f | sub-parallel to the load |"
          % (m[0]["near_axis"], m[1]["near_axis"]))
    print("| AE events | %d | %d | - |" % (m[0]["events"], m[1]["events"]))
    print("| cracks in events of 2 or more | %.2f | %.2f | clustered at low damping |"
          % (m[0]["multi"], m[1]["multi"]))
    print("| largest event (cracks) | %d | %d | larger clusters at low damping |" % (m[0]["largest"], m[1]["largest"]))
    print("| cracks per 1 %% time window before peak: coefficient of variation | %.2f | %.2f | cracking in discrete jumps at low damping |"
          % (m[0]["cv"], m[1]["cv"]))
    fmt_b = lambda x: "%.2f +- %.2f" % (x["b"], x["b_err"]) if x["b"] is not None else "n/a"
    print("| b-value (Aki) | %s | %s | - |" % (fmt_b(m[0]), fmt_b(m[1])))
    print("| blocks, steps, wall time | %d, %d, %.0f s | %d, %d, %.0f s | |"
          % (m[0]["blocks"], m[0]["steps"], m[0]["wall"], m[1]["blocks"], m[1]["steps"], m[1]["wall"]))

    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    for (s, h, c, e), label, col in zip(runs, ["alpha 0.7", "alpha 0.015"], ["C0", "C3"]):
        ax.plot(h["axial_strain"] * 100, h["axial_stress"] / 1e6, col, label=label)
        ct = np.sort(c["time"])
        ax2.plot(np.interp(ct, h["time"], h["axial_strain"]) * 100, np.arange(1, len(ct) + 1), col,
                 label=label)
    ax.set_xlabel("axial strain (%)")
    ax.set_ylabel("axial stress (MPa)")
    ax.legend(fontsize=8)
    ax2.set_xlabel("axial strain (%)")
    ax2.set_ylabel("cumulative cracks")
    ax2.legend(fontsize=8)
    fig.suptitle("B6: the same bonded specimen at two damping levels", fontsize=10)
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=130)


if __name__ == "__main__":
    main()
