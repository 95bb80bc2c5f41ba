"""Reads a vorodec CSV (history.csv, rose.csv) into columns: numbers as float arrays, the text
column `stage` as a list of strings. Shared by the postproc scripts."""
import csv
import math

import numpy as np


def read_columns(path, text_columns=("stage",)):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r]
    if not rows:
        raise ValueError("%s is empty" % path)
    header = [h.strip() for h in rows[0]]
    data = {}
    for j, name in enumerate(header):
        if name in text_columns:
            data[name] = [r[j] if j < len(r) else "" for r in rows[1:]]
            continue
        col = []
        for r in rows[1:]:
            try:
                col.append(float(r[j]))
            except (IndexError, ValueError):
                col.append(math.nan)
        data[name] = np.array(col, dtype=float)
    return data


def require(data, path, names):
    missing = [n for n in names if n not in data]
    if missing:
        raise ValueError("%s lacks column(s) %s" % (path, ", ".join(missing)))
