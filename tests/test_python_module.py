"""The Python module `beamslider` (python/): the same runs as the command
line, bit for bit; its coefficient tensor against coefficients.csv; bad input
as ValueError with the command line's message; a long run stopped from a
second thread keeps what it computed. Run by ctest with PYTHONPATH set to
build/python and BEAMSLIDER_EXECUTABLE to the built program."""

import os
import re
import signal
import subprocess
import tempfile
import threading
import unittest

import numpy as np

import beamslider

EXECUTABLE = os.environ["BEAMSLIDER_EXECUTABLE"]


def run_cli(*args):
    """The command line as a user starts it (argument vector, no shell)."""
    return subprocess.run([EXECUTABLE, *args], capture_output=True, text=True, timeout=600)


class SimulateIsTheCommandLinesRun(unittest.TestCase):
    def test_trace_periods_and_verdict_equal_the_command_lines_bit_for_bit(self):
        with tempfile.TemporaryDirectory() as tmp:
            cli = os.path.join(tmp, "cli")
            done = run_cli("simulate", "mueller2023", "--case", "signature-move", "--end-time", "2",
                           "--set", "Excitation/Frequency=123.5", "--output", cli, "--quiet")
            self.assertEqual(done.returncode, 0, done.stderr)
            scene = beamslider.Scene("mueller2023").set("Excitation/Frequency", 123.5)
            for output in (os.path.join(tmp, "py"), None):  # a kept folder, and a temporary one
                run = beamslider.simulate(scene, case="signature-move", end_time=2, output=output)
                for name, table in (("trace", run.trace), ("periods", run.periods)):
                    expected = beamslider.read_table(os.path.join(cli, name + ".csv"))
                    self.assertEqual(sorted(table), sorted(expected))
                    for column in expected:
                        self.assertTrue(np.array_equal(table[column], expected[column]), f"{name}.{column}")
                self.assertGreater(len(run.trace["t_s"]), 1000)
                summary = open(os.path.join(cli, "summary.md"), encoding="utf-8").read()
                self.assertIn("- Verdict: " + run.verdict, summary)
                self.assertEqual(run.status, "completed")
                self.assertIn(run.outcome, run.verdict)

    def test_progress_lines_reach_the_callback_and_its_exception_stops_the_run(self):
        lines = []
        beamslider.simulate(end_time=1, progress=lines.append)
        self.assertTrue(any(line.startswith("simulate mueller2023") for line in lines), lines)

        def refuse(line):
            raise LookupError("stop here")

        with self.assertRaises(LookupError):
            beamslider.simulate(end_time=1, progress=refuse)


class SweepBranchesRunSideBySide(unittest.TestCase):
    def test_both_branches_report_whole_lines_and_keep_their_order(self):
        # The branches and the free run go on two threads; their progress
        # lines reach the callback one whole line at a time.
        lines = []
        run = beamslider.sweep(from_=0.25, to=0.35, step=0.01, settle_time=0.1, average_time=0.1, free_time=0.5,
                               progress=lines.append)
        pattern = re.compile(r"^  sweep (up|down): (\d+)/11 positions, x_C/L = \d\.\d{3}, amplitude \d+\.\d{3} h, "
                             r"F_x = -?\d\.\d{2}e[-+]\d{2} N$")
        sweep_lines = [line for line in lines if line.startswith("  sweep ")]
        for line in sweep_lines:
            self.assertRegex(line, pattern)
        for direction in ("up", "down"):
            self.assertIn(f"  sweep {direction}: 11/11", " ".join(sweep_lines))
        x = run.pcs["x_over_L"]
        up, down = x[run.pcs["direction"] == "up"], x[run.pcs["direction"] == "down"]
        self.assertTrue(np.all(np.diff(up) > 0) and np.all(np.diff(down) < 0), (up, down))
        self.assertTrue(np.allclose(np.sort(up), np.sort(down), rtol=0, atol=1e-12))


class CoefficientTensor(unittest.TestCase):
    def test_tensor_holds_coefficients_csv(self):
        with tempfile.TemporaryDirectory() as tmp:
            done = run_cli("coefficients", "mueller2023", "--method", "step", "--modes", "3", "--output", tmp,
                           "--quiet")
            self.assertEqual(done.returncode, 0, done.stderr)
            csv = beamslider.read_table(os.path.join(tmp, "coefficients.csv"))
        result = beamslider.coefficients("mueller2023", method="step", modes=3)
        for column in csv:
            self.assertTrue(np.array_equal(result.table[column], csv[column]), column)
        tensor = result.tensor
        self.assertEqual(tensor.shape, (3, 3, 3, 3))
        # Symmetric in j, k, l, and each sorted entry is the sum over its permutations.
        for perm in ((0, 1, 3, 2), (0, 2, 1, 3), (0, 3, 2, 1)):
            self.assertTrue(np.allclose(tensor, tensor.transpose(perm), rtol=0, atol=0))
        scale = np.abs(csv["value"]).max()
        for n, j, k, l, value in zip(*(csv[c].astype(int) - 1 for c in "njkl"), csv["value"]):
            total = sum(tensor[n, a, b, c] for a, b, c in {(j, k, l), (j, l, k), (k, j, l), (k, l, j), (l, j, k),
                                                            (l, k, j)})
            self.assertLessEqual(abs(total - value), 1e-14 * scale)
        # The modal force of the tensor is the force of the sorted list.
        q = np.array([0.7e-6, -0.3e-6, 0.2e-6])
        f_tensor = np.einsum("njkl,j,k,l->n", tensor, q, q, q)
        f_csv = np.zeros(3)
        for n, j, k, l, value in zip(*(csv[c].astype(int) - 1 for c in "njkl"), csv["value"]):
            f_csv[n] += value * q[j] * q[k] * q[l]
        self.assertTrue(np.allclose(f_tensor, f_csv, rtol=1e-13, atol=0))


class Statics(unittest.TestCase):
    def test_load_path_equals_the_command_line_and_hardens(self):
        with tempfile.TemporaryDirectory() as tmp:
            done = run_cli("statics", "mueller2023-ideal", "--line-load", "5000", "--steps", "5", "--output", tmp,
                           "--quiet")
            self.assertEqual(done.returncode, 0, done.stderr)
            csv = beamslider.read_table(os.path.join(tmp, "statics.csv"))
        path = beamslider.statics("mueller2023-ideal", line_load=5000, steps=5).statics
        for column in csv:
            self.assertTrue(np.array_equal(path[column], csv[column]), column)
        # Downward load, downward deflection; the membrane stiffens the strip:
        # the compliance |w|/Q falls with every step.
        compliance = -path["w_mid_m"] / path["line_load_n_per_m"]
        self.assertTrue(np.all(compliance > 0))
        self.assertTrue(np.all(np.diff(compliance) < 0))
        with self.assertRaises(ValueError):
            beamslider.statics("mueller2023-ideal", line_load=0.0)


class BadInput(unittest.TestCase):
    def cli_message(self, *args):
        done = run_cli(*args)
        self.assertEqual(done.returncode, 2)
        return done.stderr.splitlines()[0]

    def test_a_bad_scene_value_raises_the_command_lines_message(self):
        expected = self.cli_message("simulate", "mueller2023", "--set", "Beam/Thickness=-0.001", "--quiet")
        self.assertIn("Thickness", expected)
        with self.assertRaises(ValueError) as raised:
            beamslider.Scene("mueller2023").set("Beam/Thickness", -0.001)
        self.assertEqual(str(raised.exception), expected)

    def test_a_bad_option_raises_the_command_lines_message(self):
        expected = self.cli_message("simulate", "mueller2023", "--end-time", "-1", "--quiet")
        with self.assertRaises(ValueError) as raised:
            beamslider.simulate(end_time=-1)
        self.assertEqual(str(raised.exception), expected)

    def test_a_missing_scene_file_raises_value_error(self):
        with self.assertRaises(ValueError) as raised:
            beamslider.Scene("/nonexistent/scene.prm")
        self.assertIn("/nonexistent/scene.prm", str(raised.exception))


class Interruption(unittest.TestCase):
    def test_a_signal_from_a_second_thread_stops_a_long_run_with_its_rows_intact(self):
        with tempfile.TemporaryDirectory() as tmp:
            trace = os.path.join(tmp, "trace.csv")

            def stop_once_rows_are_written():
                # Once the trace file holds more than its header, the run is
                # under way (no delay is assumed).
                while not (os.path.exists(trace) and os.path.getsize(trace) > 200):
                    threading.Event().wait(0.01)
                os.kill(os.getpid(), signal.SIGINT)  # as Ctrl-C does

            stopper = threading.Thread(target=stop_once_rows_are_written)
            stopper.start()
            with self.assertRaises(beamslider.Interrupted) as raised:
                beamslider.simulate(end_time=600, output=tmp)
            stopper.join()
            self.assertIsInstance(raised.exception, KeyboardInterrupt)
            partial = raised.exception.result
            self.assertIsNotNone(partial)
            self.assertEqual(partial.status, "interrupted")
            t = partial.trace["t_s"]
            self.assertGreater(len(t), 1)
            self.assertLess(t[-1], 600)
            # The run went on to the step it was in and wrote its rows up to there.
            self.assertIn("interrupted by signal 2", partial.status_message)
            self.assertGreaterEqual(len(partial.periods["t_end_s"]), 1)
            self.assertLessEqual(partial.periods["t_end_s"][-1], t[-1] + 1e-3)
            # Every row is complete and in order: nothing cut half-way.
            for column in partial.trace.values():
                self.assertEqual(len(column), len(t))
                self.assertFalse(np.isnan(column).any())
            self.assertTrue(np.all(np.diff(t) > 0))
        # Python's own Ctrl-C handler is back.
        self.assertIs(signal.getsignal(signal.SIGINT), signal.default_int_handler)

    def test_interrupt_called_from_another_thread_stops_the_run(self):
        started = threading.Event()

        def on_progress(line):
            started.set()

        def stop():
            started.wait()
            beamslider.interrupt()

        stopper = threading.Thread(target=stop)
        stopper.start()
        with self.assertRaises(beamslider.Interrupted):
            beamslider.simulate(end_time=600, progress=on_progress)
        stopper.join()
        # The next run is not stopped by the earlier request.
        self.assertEqual(beamslider.simulate(end_time=0.5).status, "completed")


class SceneFiles(unittest.TestCase):
    def test_set_get_and_write_read_back(self):
        scene = beamslider.Scene("mueller2023").set("Excitation/Frequency", 117.25)
        self.assertEqual(scene.get("Excitation/Frequency"), 117.25)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "mine.prm")
            scene.write(path)
            again = beamslider.Scene(path)
            self.assertEqual(again.parameters(), scene.parameters())
        with self.assertRaises(ValueError):
            scene.get("Excitation/No such parameter")


if __name__ == "__main__":
    unittest.main()
