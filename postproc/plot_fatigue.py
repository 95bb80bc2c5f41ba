#!/usr/bin/python3
"""Static fatigue by stress corrosion from `vorodec batch models/batch_ldb_fatigue.toml` (or any
batch of corrosion-stage runs): log10 time to failure against the driving-stress ratio, per
confinement and per layer set, with [Liu2020]'s points; and the creep curves (axial strain against
log corrosion time, one per case).

Usage: postproc/plot_fatigue.py results/batch_ldb_fatigue [-o fatigue.png] [--curves curves.png]
       [--report]

--report prints the B3 rows of verification/REPORT.md: each [Liu2020] failure time against the
case that matches it, error = |log10 t - log10 t_paper| (orders of magnitude), tolerance 1.

Reads every case folder's summary.json (corrosion_stages) and history.csv (rows labelled
`<stage>:equilibrium`). A case's series is its folder name up to `_rs`: the name says which
layers and confinement it runs (e.g. gsc_s3=0_rs0.8). Prints one row per case: series, rs,
failure time (s, and log10), corrosion steps, mechanical steps per corrosion step, and how
stepped its creep curve is before the tertiary stage: the share of the creep strain of the first
half of its life (corrosion time up to t_f / 2; the whole run if it did not fail) that the largest
5 % of those corrosion steps carry (strain from one equilibrium to the next; 0.05 for a curve of
equal steps, near 1 when a few avalanches make the curve). Needs Debian's /usr/bin/python3 with
numpy and matplotlib.
"""
import argparse
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from csvdata import read_columns  # noqa: E402

# [Liu2020]: its GSC model's failure times, s (text of section 4.2 and Fig. 16).
PAPER = {
    "unconfined": [(0.6, 139 * 86400.0), (0.8, 3.4 * 60.0)],
    "rs 0.8, s3 = 5 / 10 / 15 MPa": [(0.8, 5.0 * 60.0), (0.8, 15.5 * 60.0), (0.8, 39.1 * 60.0)],
    "rs 0.6, s3 = 15 MPa": [(0.6, 11 * 365.25 * 86400.0)],
}


def lab_fit(rs):
    """The paper's exponential fit of the LdB laboratory data (its Fig. 12): log10 t (s)."""
    return 1118.2 * np.exp(-8.2277 * rs) + 0.70239


def read_case(folder):
    with open(os.path.join(folder, "summary.json")) as f:
        summary = json.load(f)
    stages = summary.get("corrosion_stages") or []
    if not stages:
        return None
    st = stages[-1]
    data = read_columns(os.path.join(folder, "history.csv"))
    rows = [i for i, s in enumerate(data["stage"]) if s.endswith(":equilibrium")]
    return {
        "name": os.path.basename(folder.rstrip("/")),
        "rs": st["driving_stress_ratio"],
        "failure": st["failure_time_s"],
        "steps": st["corrosion_steps"],
        "per_step": st["mechanical_steps_per_corrosion_step"],
        "wall": summary.get("wall_time_s", float("nan")),
        "t": data["corrosion_time"][rows],
        "strain": data["axial_strain"][rows],
    }


def report(cases):
    by = {c["name"]: c for c in cases}

    def log_t(name):
        c = by.get(name)
        return math.log10(c["failure"]) if c and c["failure"] and c["failure"] > 0 else None

    def outcome(name):
        """The case's log10 t_f as text, or why it has none."""
        c = by.get(name)
        if c is None:
            return "not run"
        if c["failure"] is None:
            return "no failure (corrosion arrested after %d steps)" % c["steps"]
        if c["failure"] <= 0:
            return "-inf (failed as loaded)"
        return "%.3f" % math.log10(c["failure"])

    def wall(name):
        c = by.get(name)
        return "%.0f s" % c["wall"] if c else "-"

    def row(check, reference, expected_s, name, note=""):
        got = log_t(name)
        exp = math.log10(expected_s)
        err = abs(got - exp) if got is not None else float("inf")
        ok = "info" if note else ("yes" if err <= 1.0 else "**no**")
        print("| B3 | %s | %s | %.3f | %s | %.2f | 1 | %s | %s | %s%s |" % (
            check, reference, exp, outcome(name), err, ok, wall(name), name, note))

    paper = "[Liu2020], section 4.2 / Fig. 16 (GSC model)"
    row("log10 time to failure (s), rs 0.6, unconfined", paper, 139 * 86400.0, "gsc_s3=0_rs0.6")
    row("log10 time to failure (s), rs 0.8, unconfined", paper, 3.4 * 60, "gsc_s3=0_rs0.8",
        " (the rate constants were scaled to fit this point)")
    for s3, minutes in ((5, 5.0), (10, 15.5), (15, 39.1)):
        row("log10 time to failure (s), rs 0.8, s3 = %d MPa" % s3, paper, minutes * 60,
            "gsc_s3=%d_rs0.8" % s3)
    row("log10 time to failure (s), rs 0.6, s3 = 15 MPa", paper, 11 * 365.25 * 86400.0,
        "gsc_s3=15_rs0.6")
    lo, hi = log_t("gsc_s3=0_rs0.6"), log_t("gsc_s3=0_rs0.95")
    span = (lo - hi) if lo is not None and hi is not None else float("nan")
    print("| B3 | orders of magnitude of t_f from rs 0.6 to 0.95, unconfined | %s: about 6 | 6 | "
          "%s | %.2f | 1 | %s | 8 runs | gsc_s3=0_rs0.6 .. rs0.95 |" % (
              paper, "%.2f" % span if span == span else "n/a",
              abs(span - 6) if span == span else float("inf"),
              "yes" if span == span and abs(span - 6) <= 1 else "**no**"))
    seq = [log_t("gsc_s3=0_rs%g" % r) for r in (0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95)]
    known = [x for x in seq if x is not None]
    mono = len(known) == len(seq) and all(a > b for a, b in zip(known, known[1:]))
    print("| B3 | log10 t_f falls monotonically with rs (0.6-0.95, unconfined) | %s | - | %s | - | - "
          "| %s | 8 runs | %d of 8 cases failed after a finite time |" % (
              paper, "monotone" if mono else "not monotone", "yes" if mono else "**no**",
              len(known)))
    for r in (0.6, 0.7, 0.8, 0.9):
        print("| B3 | intra-grain layer alone (PSC), rs %g, unconfined: log10 t_f | [Liu2020] Fig. 12 "
              "([Potyondy2007]'s PSC): fails, sooner than GSC below rs 0.65 | - | %s | - | - | "
              "info | %s | psc_s3=0_rs%g (GSC: %s) |" % (r, outcome("psc_s3=0_rs%g" % r),
                                             wall("psc_s3=0_rs%g" % r), r,
                                             outcome("gsc_s3=0_rs%g" % r)))


def step_share(strain, fraction=0.05):
    """Share of the creep strain (the positive increments from one equilibrium to the next) that
    the largest `fraction` of the corrosion steps carry; nan without two equilibria."""
    inc = np.diff(np.asarray(strain, dtype=float))
    inc = np.sort(inc[inc > 0])[::-1]
    if inc.size == 0:
        return math.nan
    top = max(1, int(math.ceil(fraction * (len(strain) - 1))))
    return float(inc[:top].sum() / inc.sum())


def first_half(case):
    """The equilibrium strains of the first half of the case's life (all of them without a
    failure): primary and secondary creep, before the collapse's acceleration."""
    if not case["failure"] or case["failure"] <= 0:
        return case["strain"]
    return case["strain"][case["t"] <= 0.5 * case["failure"]]


def series(name):
    return name.split("_rs")[0] if "_rs" in name else name


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("folder")
    ap.add_argument("-o", "--output", default=None)
    ap.add_argument("--curves", default=None)
    ap.add_argument("--report", action="store_true")
    a = ap.parse_args()
    cases = []
    for entry in sorted(os.listdir(a.folder)):
        path = os.path.join(a.folder, entry)
        if os.path.isfile(os.path.join(path, "summary.json")):
            c = read_case(path)
            if c:
                cases.append(c)
    if not cases:
        sys.exit("%s: no corrosion-stage cases" % a.folder)
    print("series,rs,failure_time_s,log10_failure_time,corrosion_steps,mechanical_per_corrosion,"
          "top5_share")
    for c in cases:
        t = c["failure"]
        print("%s,%.3g,%s,%s,%d,%.0f,%.3f" % (series(c["name"]), c["rs"], t,
                                              "%.3f" % math.log10(t) if t and t > 0 else "",
                                              c["steps"], c["per_step"], step_share(first_half(c))))

    if a.report:
        report(cases)

    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    rs = np.linspace(0.55, 1.0, 100)
    ax.plot(rs, lab_fit(rs), "k:", lw=1, label="laboratory fit ([Liu2020], Fig. 12)")
    for label, pts in PAPER.items():
        ax.plot([p[0] for p in pts], [math.log10(p[1]) for p in pts], "s", mfc="none", ms=8,
                label="[Liu2020] GSC: " + label)
    groups = {}
    for c in cases:
        if c["failure"] and c["failure"] > 0:
            groups.setdefault(series(c["name"]), []).append((c["rs"], math.log10(c["failure"])))
    for name, pts in sorted(groups.items()):
        pts.sort()
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label="vorodec " + name)
    ax.set_xlabel("driving-stress ratio rs = (s1 - s3) / (sf - s3)")
    ax.set_ylabel("log10 time to failure (s)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    out = a.output or os.path.join(a.folder, "fatigue.png")
    fig.savefig(out, dpi=130)
    print("wrote", out)

    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    for i, c in enumerate(cases):
        keep = c["t"] > 0
        if keep.any():
            ax.semilogx(c["t"][keep], 100 * (c["strain"][keep] - c["strain"][0]),
                        color=plt.cm.tab20(i % 20),  # 16 cases: the default 10 colours repeat
                        label="%s rs %.2f" % (series(c["name"]), c["rs"]))
    ax.set_xlabel("corrosion time (s)")
    ax.set_ylabel("creep strain: axial strain since the load was on (%)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    out = a.curves or os.path.join(a.folder, "fatigue_curves.png")
    fig.savefig(out, dpi=130)
    print("wrote", out)


if __name__ == "__main__":
    main()
