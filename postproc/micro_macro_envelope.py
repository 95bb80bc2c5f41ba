#!/usr/bin/python3
"""The envelope's friction angle and cohesion against one contact or block parameter at a time,
from the results.csv of `vorodec batch models/batch_micro_macro_envelope.toml` (each case at 0
and 10 MPa confinement, per seed): a markdown table of the means ± sd over the seeds on stdout and
one panel per parameter.

Usage: postproc/micro_macro_envelope.py results/batch_micro_macro_envelope/results.csv [-o out.png]

Mohr-Coulomb from the two peaks: q = (sigma1(10) - sigma1(0)) / 10 MPa, phi = asin((q - 1) /
(q + 1)), c = UCS (1 - sin phi) / (2 cos phi). Needs Debian's /usr/bin/python3 with
python3-numpy and python3-matplotlib.
"""
import argparse
import csv
import math
import os
import statistics
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
    """Per case: each seed's envelope (from its two peaks), then their mean and sd."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    peaks = {}
    for r in rows:
        if r.get("exit_code") != "0" or not r.get("peak_stress_Pa"):
            print("skipped %s: exit code %s" % (r["case"], r.get("exit_code")), file=sys.stderr)
            continue
        name = r["case"].split("_confining_stress=")[0]
        seed = r.get("seed") or "model"
        s3 = float(r.get(SIGMA3) or 0.0)
        peaks.setdefault(name, {}).setdefault(seed, {})[s3] = (
            float(r["peak_stress_Pa"]), float(r["youngs_modulus_Pa"]), float(r["poisson_ratio"]))
    out = {}
    for name, seeds in peaks.items():
        per_seed = []
        for p in seeds.values():
            if 0.0 not in p or len(p) < 2:
                continue
            s3 = max(p)
            ucs, e, nu = p[0.0]
            q = (p[s3][0] - ucs) / s3
            phi = math.asin((q - 1) / (q + 1)) if q > 0 else float("nan")
            c = ucs * (1 - math.sin(phi)) / (2 * math.cos(phi))
            per_seed.append({"ucs": ucs, "s1": p[s3][0], "q": q, "phi": math.degrees(phi), "c": c,
                             "E": e, "nu": nu})
        if per_seed:
            out[name] = {k: (statistics.mean(v[k] for v in per_seed),
                             statistics.stdev([v[k] for v in per_seed]) if len(per_seed) > 1
                             else float("nan")) for k in per_seed[0]}
            out[name]["seeds"] = (len(per_seed), 0.0)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results")
    ap.add_argument("-o", "--output")
    args = ap.parse_args()
    env = envelopes(args.results)
    print("| case | seeds | UCS (MPa) | sigma1 at 10 MPa (MPa) | phi (deg) | c (MPa) | E (GPa) | nu |"
          "\n|---|---|---|---|---|---|---|---|")
    for name, v in env.items():
        print("| %s | %d | %.2f ± %.2f | %.2f ± %.2f | %.1f ± %.1f | %.2f ± %.2f | %.2f | %.3f |" % (
            name, v["seeds"][0], v["ucs"][0] / 1e6, v["ucs"][1] / 1e6, v["s1"][0] / 1e6,
            v["s1"][1] / 1e6, v["phi"][0], v["phi"][1], v["c"][0] / 1e6, v["c"][1] / 1e6,
            v["E"][0] / 1e9, v["nu"][0]))
    fig, axes = plt.subplots(1, len(PANELS), figsize=(3.3 * len(PANELS), 3.6), sharey=True)
    for ax, (title, (_, cases)) in zip(axes, PANELS.items()):
        pts = sorted((x, env[n]["phi"][0], env[n]["phi"][1]) for n, x in cases.items() if n in env)
        if pts:
            ax.errorbar([p[0] for p in pts], [p[1] for p in pts], yerr=[p[2] for p in pts],
                        fmt="o-", capsize=3)
        if title.startswith("dilation") and "udec_set" in env:
            ax.errorbar([18], [env["udec_set"]["phi"][0]], yerr=[env["udec_set"]["phi"][1]],
                        fmt="s", color="tab:red", capsize=3,
                        label="friction 25.5, dilation 18\n(the paper's UDEC set)")
            ax.legend(fontsize=7)
        ax.axhline(25.0, color="grey", ls="--", lw=0.8)
        ax.set_xlabel(title)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("envelope friction angle (deg), mean ± sd\nover the seeds "
                       "(dashed: the paper's 25 deg)")
    fig.tight_layout()
    out = args.output or os.path.splitext(args.results)[0] + "_envelope.png"
    fig.savefig(out, dpi=130)
    print(out, file=sys.stderr)


if __name__ == "__main__":
    main()
