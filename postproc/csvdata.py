"""Reads a vorodec CSV (history.csv, rose.csv) into columns: numbers as float arrays, the text
column `stage` as a list of strings. Shared by the postproc scripts; the file is parsed by the
Python module's reader (vorodec.read_csv, docs/python.md), taken from build/python when it is not
on PYTHONPATH."""
import math
import os
import sys

import numpy as np

try:
    import vorodec
except ImportError:
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build",
                                    "python"))
    try:
        import vorodec
    except ImportError as e:
        raise SystemExit("postproc needs the vorodec Python module: build vorodec (README) or set "
                         "PYTHONPATH to <build>/python (%s)" % e)


def _float(value):
    try:
        return float(value)
    except ValueError:
        return math.nan


def read_columns(path, text_columns=("stage",)):
    table = vorodec.read_csv(path)
    data = {}
    for name in table.dtype.names:
        column = table[name]
        if name in text_columns:
            data[name] = [str(v) for v in column]
        elif column.dtype.kind in "if":
            data[name] = column.astype(float)
        else:  # text where numbers were expected: NaN, as an unreadable number
            data[name] = np.array([_float(v) for v in column], dtype=float)
    return data


def require(data, path, names):
    missing = [n for n in names if n not in data]
    if missing:
        raise ValueError("%s lacks column(s) %s" % (path, ", ".join(missing)))
