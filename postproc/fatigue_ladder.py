#!/usr/bin/python3
"""Error against run time of the static-fatigue stage: failure time at rs 0.7 and 0.8 against n_c
(steps_per_failure), against the equilibrium limit and against the equilibrium check's interval
(check_interval, steps), from `vorodec batch
models/batch_ldb_fatigue_ladder.toml` plus the default cases (gsc_s3=0_rs0.7, gsc_s3=0_rs0.8) of
`vorodec batch models/batch_ldb_fatigue.toml` (the check interval's default rung; the n_c and
limit ladders' default rungs, every 50 steps, are rs0.7_ci50 and rs0.8_ci50 of the ladder).

Usage: postproc/fatigue_ladder.py LADDER_FOLDER FATIGUE_FOLDER [-o out_prefix]

Each ladder's reference is its finest rung (n_c 16, equilibrium 2.5e-5, a check every step);
error = |t - t_ref| / t_ref; observed order = least-squares slope of log error against log
parameter (1/n_c, the limit, or the interval). Writes <prefix>_<ladder>.csv (parameter,value,error,seconds,default,order: the input of
verification/plot_cost_accuracy.py) and prints each ladder as a Markdown table. Needs Debian's
/usr/bin/python3 with numpy.
"""
import argparse
import csv
import json
import math
import os

import numpy as np


def case(folder):
    """Failure time (s) and wall time (s) of a finished case; None if it has not finished."""
    if not os.path.isfile(os.path.join(folder, "summary.json")):
        return None
    with open(os.path.join(folder, "summary.json")) as f:
        s = json.load(f)
    st = (s.get("corrosion_stages") or [{}])[-1]
    return st.get("failure_time_s"), s["wall_time_s"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("ladder")
    ap.add_argument("fatigue")
    ap.add_argument("-o", "--out", default="fatigue_ladder")
    a = ap.parse_args()
    for rs in ("0.7", "0.8"):
        # n_c and the limit were laddered with a check every 50 steps; the interval's ladder has
        # the programme's own case (every 10) as its default.
        defaults = {"nc": case(os.path.join(a.ladder, "rs%s_ci50" % rs)),
                    "ci": case(os.path.join(a.fatigue, "gsc_s3=0_rs" + rs))}
        defaults["eq"] = defaults["nc"]
        for kind, rungs, finest in (("nc", [(1, "nc1"), (4, None), (16, "nc16")], 16),
                                    ("eq", [(4e-4, "eq4e-4"), (1e-4, None), (2.5e-5, "eq2.5e-5")],
                                     2.5e-5),
                                    ("ci", [(50, "ci50"), (10, None), (1, "ci1")], 1)):
            pts = []
            for value, name in rungs:
                got = defaults[kind] if name is None else case(
                    os.path.join(a.ladder, "rs%s_%s" % (rs, name)))
                if got is None or got[0] is None:
                    continue
                param = 1.0 / value if kind == "nc" else value
                pts.append((param, got[0], got[1], name is None, value == finest))
            label = {"nc": "1 / n_c", "eq": "equilibrium ratio", "ci": "check interval"}[kind]
            if not any(p[4] for p in pts):
                print("\n### Static fatigue, rs %s: failure time against %s\n\nNot finished "
                      "(its finest rung has no failure time).\n" % (rs, label))
                continue
            ref = [p[1] for p in pts if p[4]][0]
            rows = [(p[0], p[1], abs(p[1] - ref) / ref if p[1] and ref else float("nan"), p[2], p[3])
                    for p in pts]
            fit = [(math.log(r[0]), math.log(r[2])) for r in rows if r[2] and r[2] > 0]
            order = np.polyfit(*zip(*fit), 1)[0] if len(fit) >= 2 else float("nan")
            path = "%s_rs%s_%s.csv" % (a.out, rs, kind)
            with open(path, "w", newline="") as f:
                w = csv.writer(f)
                w.writerow(["parameter", "value", "error", "seconds", "default", "order"])
                for r in rows:
                    w.writerow([r[0], r[1], r[2], r[3], int(r[4]), order])
            print("\n### Static fatigue, rs %s: failure time against %s\n" % (rs, label))
            print("Reference: the finest rung, %.6g s. Observed order: %.2f.\n" % (ref, order))
            print("| %s | failure time (s) | error | wall time |\n|---|---|---|---|" % label)
            for r in rows:
                print("| %g%s | %.6g | %.3g | %.0f s |" % (r[0], " *" if r[4] else "", r[1], r[2],
                                                          r[3]))
            print("\n(csv: %s)" % path)


if __name__ == "__main__":
    main()
