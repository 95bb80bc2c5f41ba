#!/usr/bin/python3
"""postproc/plot_fatigue.py measures how stepped a creep curve is: equal corrosion steps give the
largest 5 % of them 5 % of the creep strain, one avalanche among small steps gives it nearly all,
and a case folder's row prints that share over the first half of the case's life.

Usage: test_plot_fatigue.py SOURCE_DIR WORK_DIR
"""
import json
import os
import subprocess
import sys


def check(what, got, want, tol):
    if not abs(got - want) <= tol:
        sys.exit("%s: %g, expected %g" % (what, got, want))


def write_case(folder, strains):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "summary.json"), "w") as f:
        json.dump({"wall_time_s": 1.0, "corrosion_stages": [{
            "driving_stress_ratio": 0.7, "failure_time_s": 1000.0,
            "corrosion_steps": len(strains) - 1, "mechanical_steps_per_corrosion_step": 50.0}]}, f)
    with open(os.path.join(folder, "history.csv"), "w") as f:
        f.write("step,corrosion_time,axial_strain,stage\n")
        for i, e in enumerate(strains):
            f.write("%d,%g,%.12g,fatigue:equilibrium\n" % (10 * i, 10.0 * i, e))
            f.write("%d,%g,%.12g,fatigue\n" % (10 * i + 5, 10.0 * i, e + 1.0))  # not an equilibrium


def main():
    source, work = sys.argv[1], sys.argv[2]
    sys.path.insert(0, os.path.join(source, "postproc"))
    import plot_fatigue

    smooth = [1e-3 + 1e-6 * i for i in range(101)]
    check("equal steps", plot_fatigue.step_share(smooth), 0.05, 1e-9)
    stepped = list(smooth)
    for i in range(50, 101):
        stepped[i] += 8.9e-4  # one avalanche of 8.9e-4 among a hundred steps of 1e-6
    check("one avalanche", plot_fatigue.step_share(stepped), (8.9e-4 + 5e-6) / 9.9e-4, 1e-9)

    folder = os.path.join(work, "batch")
    write_case(os.path.join(folder, "gsc_s3=0_rs0.7"), stepped)
    out = subprocess.run([sys.executable, os.path.join(source, "postproc", "plot_fatigue.py"),
                          folder], check=True, capture_output=True, text=True).stdout
    row = [line for line in out.splitlines() if line.startswith("gsc_s3=0,")]
    # t <= 500 s of t_f = 1000 s: 50 steps, the largest 3 carry 8.9e-4 + 3e-6 of 9.4e-4.
    if len(row) != 1 or not row[0].endswith(",0.950"):
        sys.exit("case row: %r in\n%s" % (row, out))
    print("ok")


if __name__ == "__main__":
    main()
