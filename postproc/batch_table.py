#!/usr/bin/python3
"""Plots the results.csv of `vorodec batch`: peak stress against confining stress, with a
Mohr-Coulomb fit of the peak-strength envelope.

Usage: postproc/batch_table.py results/batch_confinement/results.csv [-o out.png]

Uses the columns `loading.confining_stress` (sigma3, Pa; a case without it has sigma3 = 0) and
`peak_stress_Pa` (sigma1, Pa) of the cases whose stress passed its peak (`peak_passed`) and that
finished (exit code 0) or stopped as unstable after the peak (exit code 3: the peak was measured
before the stop). A case that ended at its highest stress has no peak to fit; it is drawn as an
open marker, a lower bound. The fit is the least-squares line sigma1 = C0 + q sigma3, read as
Mohr-Coulomb: friction angle phi = asin((q - 1) / (q + 1)), cohesion c = C0 (1 - sin phi) /
(2 cos phi); and the Hoek-Brown intact-rock curve sigma1 = sigma3 + sc sqrt(m_i sigma3 / sc + 1)
fitted as (sigma1 - sigma3)^2 = m_i sc sigma3 + sc^2 ([Hoek1997]'s regression). With one confining
stress only (a seed series) it draws each case's peak stress and their mean and standard
deviation instead. --reference-mc and --reference-hb draw a published envelope beside it.
Default output: <csv without .csv>.png.

Needs Debian's /usr/bin/python3 with python3-numpy and python3-matplotlib.
"""
import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

SIGMA3 = "loading.confining_stress"


def read_cases(path):
    """Returns (names, sigma3, sigma1) in Pa of the cases with a peak, and (sigma3, sigma1) of the
    cases that ended at their highest stress (lower bounds)."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "peak_stress_Pa" not in rows[0]:
        raise ValueError("%s: not a vorodec batch results.csv (no peak_stress_Pa column)" % path)
    names, s3, s1, bound3, bound1 = [], [], [], [], []
    for r in rows:
        code = r.get("exit_code")
        if code not in ("0", "3") or not r.get("peak_stress_Pa"):
            print("skipped %s: exit code %s" % (r.get("case"), code), file=sys.stderr)
            continue
        sigma3, sigma1 = float(r.get(SIGMA3) or 0.0), float(r["peak_stress_Pa"])
        if r.get("peak_passed") == "false":
            print("no peak in %s: %.1f MPa is a lower bound" % (r.get("case"), sigma1 / 1e6),
                  file=sys.stderr)
            bound3.append(sigma3)
            bound1.append(sigma1)
            continue
        if code == "3":
            print("%s stopped as unstable after its peak" % r.get("case"), file=sys.stderr)
        names.append(r["case"])
        s3.append(sigma3)
        s1.append(sigma1)
    return names, np.array(s3), np.array(s1), np.array(bound3), np.array(bound1)


def mohr_coulomb(s3, s1):
    """Least-squares sigma1 = C0 + q sigma3; returns (C0, q, phi in degrees, c)."""
    q, c0 = np.polyfit(s3, s1, 1)
    sin_phi = (q - 1.0) / (q + 1.0)
    phi = math.asin(max(-1.0, min(1.0, sin_phi)))
    c = c0 * (1.0 - math.sin(phi)) / (2.0 * math.cos(phi))
    return c0, q, math.degrees(phi), c


def hoek_brown(s3, s1):
    """Least-squares (sigma1 - sigma3)^2 = m_i sc sigma3 + sc^2; returns (sc, m_i)."""
    a, b = np.polyfit(s3, (s1 - s3) ** 2, 1)
    sc = math.sqrt(max(b, 0.0))
    return sc, a / sc if sc > 0 else float("nan")


def draw_references(ax, a, x):
    if a.reference_mc:
        c, phi = a.reference_mc[0] * 1e6, math.radians(a.reference_mc[1])
        q = (1 + math.sin(phi)) / (1 - math.sin(phi))
        c0 = 2 * c * math.cos(phi) / (1 - math.sin(phi))
        ax.plot(x / 1e6, (c0 + q * x) / 1e6, "--", color="gray",
                label="reference Mohr-Coulomb: c = %.1f MPa, phi = %.1f deg" % tuple(a.reference_mc))
    if a.reference_hb:
        sc, mi = a.reference_hb[0] * 1e6, a.reference_hb[1]
        ax.plot(x / 1e6, (x + sc * np.sqrt(mi * x / sc + 1)) / 1e6, ":", color="gray",
                label="reference Hoek-Brown: sc = %.1f MPa, m_i = %.1f" % tuple(a.reference_hb))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("csv")
    p.add_argument("-o", "--out")
    p.add_argument("--reference-mc", nargs=2, type=float, metavar=("C_MPA", "PHI_DEG"),
                   help="a published Mohr-Coulomb envelope to draw (cohesion MPa, friction deg)")
    p.add_argument("--reference-hb", nargs=2, type=float, metavar=("SC_MPA", "MI"),
                   help="a published Hoek-Brown curve to draw (sigma_c MPa, m_i)")
    a = p.parse_args()
    names, s3, s1, bound3, bound1 = read_cases(a.csv)
    if not names:
        sys.exit("%s: no case with a peak" % a.csv)
    out = a.out or os.path.splitext(a.csv)[0] + ".png"
    title = os.path.basename(os.path.dirname(os.path.abspath(a.csv)))
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    if len(set(s3)) >= 2:
        c0, q, phi, c = mohr_coulomb(s3, s1)
        sc, mi = hoek_brown(s3, s1)
        ax.plot(s3 / 1e6, s1 / 1e6, "o", label="cases (peak stress)")
        if len(bound3):
            ax.plot(bound3 / 1e6, bound1 / 1e6, "o", mfc="none",
                    label="no peak: highest stress (lower bound, not fitted)")
        x = np.linspace(0.0, max(s3.max(), bound3.max() if len(bound3) else 0.0), 50)
        ax.plot(x / 1e6, (c0 + q * x) / 1e6, "-",
                label="Mohr-Coulomb fit: c = %.1f MPa, phi = %.1f deg\n"
                      "sigma1 = %.1f MPa + %.2f sigma3" % (c / 1e6, phi, c0 / 1e6, q))
        ax.plot(x / 1e6, (x + sc * np.sqrt(np.maximum(mi * x / sc + 1, 0.0))) / 1e6, "-",
                label="Hoek-Brown fit: sc = %.1f MPa, m_i = %.1f" % (sc / 1e6, mi))
        draw_references(ax, a, x)
        ax.set_xlabel("confining stress sigma3 (MPa)")
        ax.set_ylabel("peak axial stress sigma1 (MPa)")
        print("Mohr-Coulomb fit of %d cases: C0 = %.2f MPa, q = %.3f, phi = %.2f deg, c = %.2f MPa"
              % (len(names), c0 / 1e6, q, phi, c / 1e6))
        print("Hoek-Brown fit of %d cases: sc = %.2f MPa, m_i = %.2f" % (len(names), sc / 1e6, mi))
    else:
        mean, std = s1.mean(), s1.std(ddof=1) if len(s1) > 1 else 0.0
        ax.bar(range(len(names)), s1 / 1e6)
        ax.axhline(mean / 1e6, color="k", label="mean %.2f MPa, std %.2f MPa" % (mean / 1e6, std / 1e6))
        ax.set_xticks(range(len(names)), names, rotation=45, ha="right", fontsize=7)
        ax.set_ylabel("peak axial stress (MPa)")
        print("peak stress of %d cases: mean %.2f MPa, std %.2f MPa" % (len(names), mean / 1e6, std / 1e6))
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print("wrote %s" % out)


if __name__ == "__main__":
    main()
