#!/usr/bin/python3
"""postproc/batch_table.py fits the envelope it is given: exact Mohr-Coulomb and Hoek-Brown peaks
come back as their parameters, a peak measured before an instability stop (exit 3) is fitted, and
a run without a peak or a failed run is not.

Usage: test_batch_table.py SOURCE_DIR WORK_DIR
"""
import csv
import math
import os
import re
import subprocess
import sys

HEADER = ["case", "loading.confining_stress", "exit_code", "peak_stress_Pa", "peak_passed"]


def write(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(HEADER)
        w.writerows(rows)


def fit(script, path):
    out = subprocess.run([sys.executable, script, path, "-o", path + ".png"], check=True,
                         capture_output=True, text=True)
    mc = re.search(r"phi = ([\d.]+) deg, c = ([\d.]+) MPa", out.stdout)
    hb = re.search(r"sc = ([\d.]+) MPa, m_i = ([\d.]+)", out.stdout)
    n = re.search(r"Mohr-Coulomb fit of (\d+) cases", out.stdout)
    return int(n.group(1)), float(mc.group(1)), float(mc.group(2)), float(hb.group(1)), float(hb.group(2))


def check(what, got, want, tol):
    if abs(got - want) > tol:
        sys.exit("%s: %g, expected %g" % (what, got, want))


def main():
    script = os.path.join(sys.argv[1], "postproc", "batch_table.py")
    work = sys.argv[2]
    os.makedirs(work, exist_ok=True)

    # Mohr-Coulomb c 50 MPa, phi 45 deg: sigma1 = 2 c cos(phi) / (1 - sin(phi)) + q sigma3.
    phi = math.radians(45.0)
    q = (1 + math.sin(phi)) / (1 - math.sin(phi))
    c0 = 2 * 50e6 * math.cos(phi) / (1 - math.sin(phi))
    rows = [["s3=%g" % s3, s3, code, c0 + q * s3, "true"]
            for s3, code in [(0, "0"), (10e6, "0"), (20e6, "3"), (40e6, "0")]]
    rows.append(["no_peak", 60e6, "0", 9e9, "false"])  # off the line: must not be fitted
    rows.append(["failed", 30e6, "2", 1.0, "true"])
    path = os.path.join(work, "mohr_coulomb.csv")
    write(path, rows)
    n, got_phi, got_c, _, _ = fit(script, path)
    if n != 4:
        sys.exit("fitted %d cases, expected the four with a peak (one of them exit 3)" % n)
    check("phi (deg)", got_phi, 45.0, 0.01)
    check("c (MPa)", got_c, 50.0, 0.01)

    # Hoek-Brown sc 200 MPa, m_i 20.
    sc, mi = 200e6, 20.0
    rows = [["s3=%g" % s3, s3, "0", s3 + sc * math.sqrt(mi * s3 / sc + 1), "true"]
            for s3 in (0.0, 5e6, 15e6, 30e6, 60e6)]
    path = os.path.join(work, "hoek_brown.csv")
    write(path, rows)
    _, _, _, got_sc, got_mi = fit(script, path)
    check("sc (MPa)", got_sc, 200.0, 0.01)
    check("m_i", got_mi, 20.0, 0.01)
    print("batch_table fits: ok")


if __name__ == "__main__":
    main()
