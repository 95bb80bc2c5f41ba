"""A run's results folder read into Python: summary.json as a dict, each CSV file as a numpy
structured array (docs/python.md#results)."""
import csv
import json
import math
from pathlib import Path

import numpy as np


def _column(values):
    """Integers where every value is one, else floats where every value is one (an empty cell is
    NaN), else text."""
    try:
        return np.array([int(v) for v in values], dtype=np.int64)
    except ValueError:
        pass
    try:
        return np.array([float(v) if v != "" else math.nan for v in values], dtype=np.float64)
    except ValueError:
        return np.array(values, dtype=str)


def read_csv(path):
    """A vorodec CSV file as a numpy structured array, one field per column in file order."""
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r]
    if not rows:
        raise ValueError("%s is empty (no header)" % path)
    header = [h.strip() for h in rows[0]]
    body = rows[1:]
    for i, r in enumerate(body):
        if len(r) != len(header):
            raise ValueError("%s:%d: %d fields, the header has %d" % (path, i + 2, len(r), len(header)))
    columns = [_column([r[j] for r in body]) for j in range(len(header))]
    dtype = [(name, c.dtype if len(body) else np.float64) for name, c in zip(header, columns)]
    table = np.empty(len(body), dtype=dtype)
    for name, c in zip(header, columns):
        table[name] = c
    return table


class Result:
    """What a run left in its folder. Tables are read when first asked for; a file the run did not
    write (cycles.csv of a monotonic test, summary.json of a stopped run) gives None."""

    def __init__(self, out, exit_code=None, status=None):
        self.out = Path(out)
        if not self.out.is_dir():
            raise FileNotFoundError("%s: no such results folder" % self.out)
        self._tables = {}
        self._summary = None
        self.exit_code = exit_code
        self.status = status if status is not None else (self.summary or {}).get("status")

    def __repr__(self):
        return "vorodec.Result(%r, status=%r)" % (str(self.out), self.status)

    @property
    def summary(self):
        """summary.json as a dict (None before the run has finished)."""
        if self._summary is None:
            path = self.out / "summary.json"
            if path.exists():
                self._summary = json.loads(path.read_text())
        return self._summary

    def table(self, name):
        """<out>/<name>.csv as a structured array, or None when the run wrote no such file."""
        if name not in self._tables:
            path = self.out / (name + ".csv")
            self._tables[name] = read_csv(path) if path.exists() else None
        return self._tables[name]

    def dataframe(self, name="history"):
        """A table as a pandas DataFrame (pandas is optional: Debian's python3-pandas)."""
        import pandas

        table = self.table(name)
        return None if table is None else pandas.DataFrame.from_records(table)

    history = property(lambda self: self.table("history"), doc="history.csv: one row per sample")
    cracks = property(lambda self: self.table("cracks"), doc="cracks.csv: one row per crack")
    cycles = property(lambda self: self.table("cycles"), doc="cycles.csv: one row per load cycle")
    ae_events = property(lambda self: self.table("ae_events"), doc="ae_events.csv: AE catalogue")
    rose = property(lambda self: self.table("rose"), doc="rose.csv: crack orientations in time")

    @property
    def vtk(self):
        """The ParaView series (<out>/vtk/*.pvd), or None when the run wrote none."""
        series = sorted((self.out / "vtk").glob("*.pvd"))
        return series[0] if series else None


def load(out):
    """The results of a finished (or stopped) run in folder `out`, without running anything."""
    return Result(out)
