#!/usr/bin/python3
"""The envelope's friction angle and cohesion against one contact or block parameter at a time,
from the results.csv of `vorodec batch models/batch_micro_macro_envelope.toml` (each case at 0
and 10 MPa confinement): a markdown table on stdout and one panel per parameter.

Usage: postproc/micro_macro_envelope.py results/batch_micro_macro_envelope/results.csv [-o out.png]

Mohr-Coulomb from the two peaks: q = (sigma1(10) - sigma1(0)) / 10 MPa, phi = asin((q - 1) /
(q + 1)), c = UCS (1 - sin phi) / (2 cos phi). Needs Debian's /usr/bin/python3 with
python3-numpy and python3-matplotlib.
"""
import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SIGMA3 = "loading.confining_stress"
# case -> (panel, parameter value); "base" belongs to every panel at the model's values.
PANELS = {
    "contact friction (deg), dilation 0": ("friction", {"friction0": 0, "friction5": 5, "base": 10,
                                                        "friction15": 15, "friction25.5": 25.5}),
    "dilation (deg), friction 10 deg": ("dilation", {"base": 0, "dilation18": 18}),
    "rounding length (mm)": ("rounding", {"rounding0.05mm": 0.05, "base": 0.1,
                                          "rounding0.12mm": 0.12}),
    "minimum edge length (mm)": ("min_edge", {"min_edge0.2mm": 0.2, "base": 0.25,
                                              "min_edge0.5mm": 0.5}),
    "Lloyd sweeps": ("lloyd", {"lloyd0": 0, "base": 2, "lloyd10": 10}),
}


def envelopes(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    peaks = {}
    for r in rows:
        if r.get("exit_code") != "0" or not r.get("peak_stress_Pa"):
            print("skipped %s: exit code %s" % (r["case"], r.get("exit_code")), file=sys.stderr)
            continue
        name = r["case"].split("_confining_stress=")[0]
        s3 = float(r.get(SIGMA3) or 0.0)
        peaks.setdefault(name, {})[s3] = (float(r["peak_stress_Pa"]), float(r["youngs_modulus_Pa"]),
                                          float(r["poisson_ratio"]))
    out = {}
    for name, p in peaks.items():
        if 0.0 not in p or len(p) < 2:
            continue
        s3 = max(p)
        ucs, e, nu = p[0.0]
        q = (p[s3][0] - ucs) / s3
        phi = math.asin((q - 1) / (q + 1)) if q > 0 else float("nan")
        c = ucs * (1 - math.sin(phi)) / (2 * math.cos(phi))
        out[name] = {"ucs": ucs, "s1": p[s3][0], "q": q, "phi": math.degrees(phi), "c": c, "E": e,
                     "nu": nu}
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results")
    ap.add_argument("-o", "--output")
    args = ap.parse_args()
    env = envelopes(args.results)
    print("| case | UCS (MPa) | sigma1 at 10 MPa (MPa) | slope q | phi (deg) | c (MPa) | E (GPa) "
          "| nu |\n|---|---|---|---|---|---|---|---|")
    for name, v in env.items():
        print("| %s | %.2f | %.2f | %.3f | %.1f | %.2f | %.2f | %.3f |" % (
            name, v["ucs"] / 1e6, v["s1"] / 1e6, v["q"], v["phi"], v["c"] / 1e6, v["E"] / 1e9,
            v["nu"]))
    fig, axes = plt.subplots(1, len(PANELS), figsize=(3.3 * len(PANELS), 3.6), sharey=True)
    for ax, (title, (_, cases)) in zip(axes, PANELS.items()):
        pts = sorted((x, env[n]["phi"]) for n, x in cases.items() if n in env)
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-")
        if title.startswith("dilation") and "udec_set" in env:
            ax.plot([18], [env["udec_set"]["phi"]], "s", color="tab:red",
                    label="friction 25.5, dilation 18\n(the paper's UDEC set)")
            ax.legend(fontsize=7)
        ax.axhline(25.0, color="grey", ls="--", lw=0.8)
        ax.set_xlabel(title)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("envelope friction angle (deg)\n(dashed: the paper's 25 deg)")
    fig.tight_layout()
    out = args.output or os.path.splitext(args.results)[0] + "_envelope.png"
    fig.savefig(out, dpi=130)
    print(out, file=sys.stderr)


if __name__ == "__main__":
    main()
