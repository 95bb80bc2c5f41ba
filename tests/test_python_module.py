"""The Python module against the command: same numbers, same errors, a stop with a checkpoint on
Ctrl-C, the GIL released while a run steps. Run by ctest with Debian's /usr/bin/python3:
    test_python_module.py <vorodec source folder> <scratch folder>
"""
import filecmp
import json
import os
import signal
import subprocess
import sys
import threading
import unittest
from pathlib import Path

import numpy as np

import vorodec

SOURCE = Path(sys.argv[1])
SCRATCH = Path(sys.argv[2])
SMALL = SOURCE / "tests" / "models" / "e2e_small.toml"  # ~170 blocks, 5,900 steps


def cli(*args):
    return subprocess.run([str(vorodec._core.cli), *map(str, args)], capture_output=True, text=True)


def same_summary(a, b):
    """summary.json of two runs: equal but for their wall times."""
    a, b = dict(a), dict(b)
    for s in (a, b):
        s.pop("wall_time_s")
    return a == b


class RunMatchesCommand(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.cli_out, cls.py_out = SCRATCH / "cli", SCRATCH / "python"
        done = cli("run", SMALL, "--out", cls.cli_out, "--no-vtk", "--threads", "1",
                   "--set", "seed=12", "--set", "joints.friction=30")
        assert done.returncode == 0, done.stderr
        cls.result = vorodec.run(SMALL, out=cls.py_out, vtk=False, threads=1,
                                 set={"seed": 12, "joints.friction": 30.0})

    def test_run_writes_the_files_the_command_writes_byte_for_byte(self):
        for name in ("history.csv", "cracks.csv", "rose.csv", "ae_events.csv"):
            self.assertTrue(filecmp.cmp(self.cli_out / name, self.py_out / name, shallow=False),
                            name)
        cli_summary = json.loads((self.cli_out / "summary.json").read_text())
        self.assertTrue(same_summary(cli_summary, self.result.summary))

    def test_history_holds_the_numbers_of_the_command_history_file(self):
        text = (self.cli_out / "history.csv").read_text().splitlines()
        header = text[0].split(",")
        rows = [line.split(",") for line in text[1:]]
        h = self.result.history
        self.assertEqual(list(h.dtype.names), header)
        self.assertEqual(len(h), len(rows))
        self.assertEqual(h["step"].dtype, np.int64)
        for j, name in enumerate(header):
            column = [r[j] for r in rows]
            if name == "stage":
                self.assertEqual(list(h[name]), column)
            else:
                np.testing.assert_array_equal(h[name], np.array(column, dtype=float), name)

    def test_result_reports_the_run(self):
        r = self.result
        self.assertEqual(r.exit_code, 0)
        self.assertEqual(r.status, "finished")
        self.assertGreater(r.summary["peak_stress_Pa"], 1e6)
        self.assertEqual(len(r.cracks), r.summary["cracks"]["tensile"] + r.summary["cracks"]["shear"])
        self.assertIsNone(r.cycles)  # a monotonic test writes no cycles.csv
        self.assertIsNone(r.vtk)

    def test_load_reads_a_finished_run_as_run_returned_it(self):
        loaded = vorodec.load(self.py_out)
        self.assertEqual(loaded.summary, self.result.summary)
        self.assertEqual(loaded.status, "finished")
        np.testing.assert_array_equal(loaded.history, self.result.history)

    def test_set_changes_the_run_as_the_command_set_does(self):
        plain = vorodec.run(SMALL, out=SCRATCH / "plain", vtk=False, max_steps=300)
        other = vorodec.run(SMALL, out=SCRATCH / "seed12", vtk=False, max_steps=300,
                            set={"seed": 12, "joints.friction": 30.0})
        self.assertEqual(other.status, "stopped at --max-steps")  # as the command says
        self.assertFalse(np.array_equal(plain.history["axial_stress"],
                                        other.history["axial_stress"]))
        # The same run up to the step limit, whose row closes the stage ("load:end").
        n = len(other.history) - 1
        np.testing.assert_array_equal(other.history[:n], self.result.history[:n])


class BadInputRaises(unittest.TestCase):
    def test_a_misspelled_key_raises_input_error_with_file_key_and_line(self):
        bad = SCRATCH / "misspelled.toml"
        bad.write_text(SMALL.read_text().replace("dilation =", "dilaton ="))
        with self.assertRaises(vorodec.InputError) as e:
            vorodec.run(bad, out=SCRATCH / "bad")
        message = str(e.exception)
        self.assertIn(str(bad), message)
        self.assertIn("'joints.dilaton': unknown key (did you mean 'dilation'?)", message)
        self.assertRegex(message, r"misspelled\.toml:\d+")
        self.assertFalse(message.startswith("error"))  # the message alone, as the CLI prints it
        done = cli("check", bad)
        self.assertEqual(done.returncode, 2)
        self.assertEqual(done.stderr.strip(), "error: " + message)

    def test_a_bad_set_value_raises_and_names_set(self):
        with self.assertRaises(vorodec.InputError) as e:
            vorodec.check(SMALL, set={"joints.jkn": -1.0})
        self.assertIn("jkn", str(e.exception))
        with self.assertRaises(vorodec.InputError):
            vorodec.check(SMALL, set={"joints.no_such_key": 1})

    def test_check_reports_the_specimen_and_build_writes_it(self):
        report = vorodec.check(SMALL)
        self.assertEqual(report["load_path"], "1 stages")
        self.assertIn("blocks:", report["report"])
        self.assertGreater(report["blocks"], 100)
        self.assertNotIn("specimen_file", report)  # check writes nothing
        built = vorodec.build(SMALL, out=SCRATCH / "built")
        self.assertEqual(built["blocks"], report["blocks"])
        self.assertTrue(built["specimen_file"].exists())

    def test_resume_of_a_folder_without_checkpoint_raises_input_error(self):
        (SCRATCH / "empty").mkdir(exist_ok=True)
        with self.assertRaises(vorodec.InputError):
            vorodec.resume(SCRATCH / "empty")


class UnstableRunRaises(unittest.TestCase):
    def test_an_unstable_run_raises_with_the_state_it_wrote(self):
        # Rounded corners 100 times thinner than the model's: the first overlaps exceed their limit.
        with self.assertRaises(vorodec.UnstableError) as e:
            vorodec.run(SMALL, out=SCRATCH / "unstable", vtk=False,
                        set={"contact.rounding_length": 2e-6})
        self.assertIn("contact overlap too great", str(e.exception))
        self.assertEqual(e.exception.out, SCRATCH / "unstable")
        self.assertTrue(e.exception.result.summary["status"].startswith("unstable"))
        self.assertGreater(len(e.exception.result.history), 1)


class InterruptAndThreads(unittest.TestCase):
    def test_sigint_stops_with_a_checkpoint_and_resume_finishes_byte_identical(self):
        whole = vorodec.run(SMALL, out=SCRATCH / "whole", vtk=False)
        stopped = SCRATCH / "interrupted"
        sent = []

        def interrupt(report):
            if not sent:  # a Ctrl-C while the run steps
                sent.append(report["steps"])
                os.kill(os.getpid(), signal.SIGINT)

        with self.assertRaises(KeyboardInterrupt) as e:
            vorodec.run(SMALL, out=stopped, vtk=False, callback=interrupt)
        self.assertIn("vorodec.resume", str(e.exception))
        self.assertTrue((stopped / "checkpoint.vck").exists())
        self.assertIs(signal.getsignal(signal.SIGINT), signal.default_int_handler)
        finished = vorodec.resume(stopped)
        self.assertEqual(finished.exit_code, 0)
        for name in ("history.csv", "cracks.csv"):
            self.assertTrue(filecmp.cmp(whole.out / name, stopped / name, shallow=False), name)
        self.assertTrue(same_summary(whole.summary, finished.summary))

    def test_an_exception_in_the_callback_stops_the_run_with_a_checkpoint(self):
        def fail(report):
            raise ValueError("enough at step %d" % report["steps"])

        with self.assertRaisesRegex(ValueError, "enough at step"):
            vorodec.run(SMALL, out=SCRATCH / "callback", vtk=False, callback=fail)
        self.assertTrue((SCRATCH / "callback" / "checkpoint.vck").exists())

    def test_a_run_in_a_thread_lets_other_python_threads_run(self):
        counter = [0]
        seen = []  # the other thread's count at each progress report
        worker = threading.Thread(target=lambda: vorodec.run(
            SMALL, out=SCRATCH / "threaded", vtk=False, threads=1,
            callback=lambda report: seen.append(counter[0])))
        worker.start()
        while worker.is_alive():
            counter[0] += 1
        worker.join()
        self.assertGreater(len(seen), 3)
        # Held through the run, the GIL would let the loop count nothing between reports.
        self.assertGreater(seen[-1], seen[0])
        self.assertEqual(vorodec.load(SCRATCH / "threaded").status, "finished")


class Workflows(unittest.TestCase):
    def test_batch_runs_every_case_and_returns_their_results(self):
        out = SCRATCH / "batch"
        b = vorodec.batch(SOURCE / "tests" / "models" / "batch_small.toml", out=out, max_steps=200,
                          vtk=False, jobs=2)
        self.assertEqual(len(b["table"]), len(b["cases"]))
        for name, r in b["cases"].items():
            self.assertIsNotNone(r.history, name)
        self.assertTrue((out / "results.csv").exists())

    def test_calibrate_check_validates_without_running(self):
        c = vorodec.calibrate(SOURCE / "tests" / "models" / "calibrate_small.toml", check=True)
        self.assertEqual(c["exit_code"], 0)
        self.assertIsNone(c["report"])

    def test_laws_lists_the_contact_laws(self):
        self.assertIn("mohr_coulomb", vorodec.laws())


if __name__ == "__main__":
    SCRATCH.mkdir(parents=True, exist_ok=True)
    os.chdir(SOURCE)  # model files name others relative to themselves; outputs go to SCRATCH
    unittest.main(argv=sys.argv[:1], verbosity=2)
