#!/usr/bin/python3
"""A study in Python: the marble's strength envelope from triaxial runs at several confining
stresses, the Mohr-Coulomb cohesion and friction angle fitted to the peaks, and the stress-strain
curves in one figure. The same study from the command line is `vorodec batch
models/batch_confinement.toml` and a script over its results.csv.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/confinement_envelope.py [--short]

--short (what CI runs, seconds): a 25 x 50 mm specimen of 326 blocks at 0 and 10 MPa. The full study: the
model's 1,302 blocks at 0, 5, 10 and 15 MPa, about two minutes on 2 cores.
Fit (docs/python.md#the-example-study): sigma1 = UCS + q sigma3 by least squares,
phi = asin((q - 1) / (q + 1)), c = UCS (1 - sin phi) / (2 cos phi).
"""
import argparse
import math
import sys
from pathlib import Path

import numpy as np

import vorodec

ROOT = Path(__file__).resolve().parents[2]
MODEL = ROOT / "models" / "triaxial_marble.toml"


def mohr_coulomb(sigma3, sigma1):
    """Cohesion (Pa), friction angle (deg), UCS (Pa) and slope q of the line through the peaks."""
    q, ucs = np.polyfit(sigma3, sigma1, 1)
    phi = math.asin((q - 1) / (q + 1))
    return ucs * (1 - math.sin(phi)) / (2 * math.cos(phi)), math.degrees(phi), ucs, q


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--short", action="store_true", help="a small specimen, two confinements")
    parser.add_argument("--out", default="results/confinement_envelope", help="results folder")
    parser.add_argument("--plot", help="the figure's file (PNG); none without it")
    args = parser.parse_args()

    confinements = [0.0, 10e6] if args.short else [0.0, 5e6, 10e6, 15e6]  # Pa
    # Short: a 25 x 50 mm specimen with the model's block size (326 blocks), four times cheaper.
    common = ({"specimen.width": 0.025, "specimen.height": 0.05, "specimen.block_count": 326}
              if args.short else {})
    runs = {}
    for s3 in confinements:
        out = Path(args.out) / ("s3_%gMPa" % (s3 / 1e6))
        runs[s3] = vorodec.run(MODEL, out=out, vtk=False,
                               set={**common, "loading.confining_stress": s3})
        print("sigma3 %5.1f MPa: peak %7.2f MPa, E %5.1f GPa, %s" % (
            s3 / 1e6, runs[s3].summary["peak_stress_Pa"] / 1e6,
            runs[s3].summary["youngs_modulus_Pa"] / 1e9, runs[s3].status))
        stress = runs[s3].history["axial_stress"]
        if stress[-1] >= 0.99 * stress.max():  # a strength needs a peak, not the strain limit
            print("  warning: no peak before the strain limit; the fit uses the last stress")

    sigma3 = np.array(confinements)
    # The peak axial stress is sigma1 itself: the platens' stress, not a deviator.
    sigma1 = np.array([runs[s3].summary["peak_stress_Pa"] for s3 in confinements])
    c, phi, ucs, q = mohr_coulomb(sigma3, sigma1)
    print("Mohr-Coulomb over %g-%g MPa: c %.2f MPa, phi %.1f deg (UCS of the fit %.2f MPa)" % (
        sigma3[0] / 1e6, sigma3[-1] / 1e6, c / 1e6, phi, ucs / 1e6))

    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, (curves, envelope) = plt.subplots(1, 2, figsize=(10, 4))
        for s3, r in runs.items():
            h = r.history
            curves.plot(100 * h["axial_strain"], h["axial_stress"] / 1e6,
                        label="%g MPa" % (s3 / 1e6))
        curves.set(xlabel="axial strain (%)", ylabel="axial stress (MPa)")
        curves.legend(title="confinement")
        envelope.plot(sigma3 / 1e6, sigma1 / 1e6, "o", label="peaks")
        envelope.plot(sigma3 / 1e6, (ucs + q * sigma3) / 1e6, "-",
                      label="c %.1f MPa, phi %.1f deg" % (c / 1e6, phi))
        envelope.set(xlabel="sigma3 (MPa)", ylabel="sigma1 at peak (MPa)")
        envelope.legend()
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
        print("figure:", args.plot)
    return 0 if all(r.exit_code == 0 for r in runs.values()) else 1


if __name__ == "__main__":
    sys.exit(main())
