"""vorodec from Python: check, build, run, resume, batch and calibrate model files in this process
with the library the `vorodec` command uses, and read results as numpy arrays (docs/python.md).

    import vorodec
    r = vorodec.run("models/ucs_marble.toml", out="results/marble", set={"seed": 7})
    r.summary["peak_stress_Pa"], r.history["axial_stress"]
"""
import json
import math
import signal
from pathlib import Path

from . import _core
from ._core import InputError, __version__
from .results import Result, load, read_csv

__all__ = ["InputError", "UnstableError", "Result", "load", "read_csv", "check", "build", "run",
           "resume", "batch", "calibrate", "laws", "__version__"]

# The command's exit codes (docs/command-line.md#exit-codes).
UNSTABLE, STOPPED_FOR_RESUME = 3, 6


class UnstableError(RuntimeError):
    """The run stopped unstable (NaN or a blow-up; exit code 3). `out` is its folder, `result` what
    it wrote up to its last good state."""

    def __init__(self, message, result):
        super().__init__(message)
        self.result = result
        self.out = result.out


def _toml(value):
    """A Python value as the TOML text a `--set KEY=VALUE` would give."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        return repr(value) if math.isfinite(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, (str, Path)):
        return json.dumps(str(value))  # a TOML basic string
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join("%s = %s" % (k, _toml(v)) for k, v in value.items()) + " }"
    raise TypeError("set: %r is not a TOML value (bool, number, string, list or dict)" % (value,))


def _overrides(set):
    return [(str(k), _toml(v)) for k, v in (set or {}).items()]


def _out(model, out):
    return Path(out) if out is not None else Path("results") / Path(model).stem


def _finish(outcome):
    """The Result of a run that returned, or the exception its exit code means."""
    result = Result(outcome["out"], outcome["exit_code"], outcome["status"])
    if outcome["exit_code"] == STOPPED_FOR_RESUME and outcome["signal"] == signal.SIGINT:
        interrupt = KeyboardInterrupt(
            "%s; vorodec.resume(%r) continues it" % (outcome["status"], str(result.out)))
        interrupt.result = result
        raise interrupt
    if outcome["exit_code"] == STOPPED_FOR_RESUME and outcome["signal"]:
        # SIGTERM: the checkpoint is written; the process ends as the signal would have ended it.
        raise SystemExit(128 + outcome["signal"])
    if outcome["exit_code"] == UNSTABLE:
        raise UnstableError("%s: %s" % (result.out, outcome["status"]), result)
    return result


def check(model, set=None):
    """Reads the model file and builds its specimen, runs nothing. A dict: blocks, report (the
    geometry report `vorodec check` prints), warnings, load_path. Bad input raises InputError."""
    return _core.specimen(Path(model), _overrides(set), "")  # "": no folder, nothing written


def build(model, out=None, set=None):
    """As check, and writes the specimen to <out>/specimen.vsp (for `specimen.file`)."""
    return _core.specimen(Path(model), _overrides(set), _out(model, out))


def run(model, out=None, set=None, threads=0, max_steps=0, vtk=True, stop_at_step=0,
        progress=False, callback=None):
    """Runs a model file to the end of its load path in this process, as `vorodec run` does.

    out: results folder (default results/<model name>); set: model-file keys overridden, as
    --set ({"loading.confining_stress": 5e6}); threads: OpenMP threads (0: all cores);
    max_steps, vtk, stop_at_step: as the command's options; progress: the command's progress line
    on stderr; callback: called with a dict (stage, stages, stage_name, steps, stress [Pa],
    fraction, waiting, clock) as often as the progress line is drawn. An exception it raises stops
    the run with a checkpoint and is raised again.

    The GIL is released while the run steps. Ctrl-C (SIGINT) stops it with a checkpoint and raises
    KeyboardInterrupt; vorodec.resume(out) continues it. Returns a Result; raises InputError on
    bad input and UnstableError when the run stops unstable.
    """
    outcome = _core.run(Path(model), _overrides(set), _out(model, out), threads, max_steps, vtk,
                        stop_at_step, progress, callback)
    return _finish(outcome)


def resume(out, threads=0, stop_at_step=0, progress=False, callback=None):
    """Continues the stopped run whose checkpoint is in `out`, as `vorodec resume` does."""
    return _finish(_core.resume(Path(out), threads, stop_at_step, progress, callback))


def batch(batch_file, out=None, jobs=0, max_steps=0, vtk=True):
    """Runs every case of a batch file (each a `vorodec run` process), as `vorodec batch` does.
    A dict: exit_code (0 every case finished, 5 some did not), out, table (results.csv as a
    structured array) and cases (case name -> Result)."""
    code, folder = _core.batch(Path(batch_file), out or "", jobs, max_steps, vtk)
    if code == 2:
        raise InputError("%s: bad input (its message is above)" % batch_file)
    table = read_csv(folder / "results.csv")
    cases = {name: Result(folder / name) for name in table["case"]}
    return {"exit_code": code, "out": folder, "table": table, "cases": cases}


def calibrate(calibration_file, out=None, jobs=0, check=False):
    """Fits model parameters to laboratory targets, as `vorodec calibrate` does. A dict: exit_code
    (0 every target met, 5 the budget ran out first), out, and report (report.md's text)."""
    code, folder = _core.calibrate(Path(calibration_file), out or "", jobs, check)
    if code == 2:
        raise InputError("%s: bad input (its message is above)" % calibration_file)
    if code == STOPPED_FOR_RESUME:
        raise KeyboardInterrupt("calibration stopped; run it again to continue")
    report = folder / "report.md"
    return {"exit_code": code, "out": folder,
            "report": report.read_text() if report.exists() and not check else None}


def laws():
    """The contact laws' model-file keys, as `vorodec laws` prints them."""
    return _core.laws()
