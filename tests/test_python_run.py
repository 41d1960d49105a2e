"""beamslider.Run, the run held in the Python process: its trace and periods
are the command line's `simulate` files to the last written digit (ROM and
FE); a checkpoint resumes bit for bit; steps in pieces equal one advance;
Ctrl-C raises KeyboardInterrupt and the run goes on as if never stopped; bad
input and foreign checkpoints raise ValueError with the reason. Run by ctest
with PYTHONPATH set to build/python and BEAMSLIDER_EXECUTABLE to the built
program."""

import csv
import os
import signal
import subprocess
import tempfile
import threading
import unittest

import numpy as np

import beamslider

EXECUTABLE = os.environ["BEAMSLIDER_EXECUTABLE"]


def simulate_cli(folder, *args):
    done = subprocess.run([EXECUTABLE, "simulate", "mueller2023", *args, "--output", folder, "--quiet"],
                          capture_output=True, text=True, timeout=600)
    if done.returncode != 0:
        raise AssertionError(done.stderr)


def csv_rows(path):
    with open(path, newline="", encoding="utf-8") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    return rows[0], rows[1:]


def as_written(table, header):
    """The rows as the command line writes them: 10 significant digits (C++
    precision 10 is printf's %.10g), counts as integers."""
    def cell(name, x):
        return str(int(x)) if name in ("period", "max_solver_iterations") else "%.10g" % x
    n = len(table[header[0]])
    return [[cell(name, table[name][i]) for name in header] for i in range(n)]


class RunIsSimulatesRun(unittest.TestCase):
    def check_against_cli(self, model, seconds, overrides=()):
        scene = beamslider.Scene("mueller2023")
        args = ["--model", model, "--end-time", repr(seconds)]
        for parameter, value in overrides:
            scene.set(parameter, value)
            args += ["--set", f"{parameter}={value!r}"]
        run = beamslider.Run(scene, model=model)
        self.assertEqual(run.advance(seconds), "completed")
        self.assertAlmostEqual(run.t, seconds, delta=1e-9)
        with tempfile.TemporaryDirectory() as tmp:
            simulate_cli(tmp, *args)
            for name, table in (("trace", run.trace), ("periods", run.periods)):
                header, rows = csv_rows(os.path.join(tmp, name + ".csv"))
                self.assertEqual(sorted(header), sorted(table), name)
                self.assertEqual(as_written(table, header), rows, name)
            with open(os.path.join(tmp, "summary.md"), encoding="utf-8") as f:
                summary = f.read()
            self.assertIn("- Verdict: " + run.analyse()["verdict"], summary)
        return run

    def test_rom_trace_periods_and_verdict_equal_simulates_files(self):
        run = self.check_against_cli("rom", 3.0, [("Excitation/Frequency", 123.5)])
        self.assertEqual(len(run.trace["t_s"]), 3001)
        self.assertEqual(len(run.state["q"]), int(beamslider.Scene().get("Discretisation/Number of modes")))

    def test_fe_trace_equals_simulates_files(self):
        self.check_against_cli("fe", 0.05)

    def test_steps_in_pieces_equal_one_advance(self):
        whole = beamslider.Run()
        whole.advance(0.4)
        pieces = beamslider.Run()
        for n in (1, 999, 4000, 15000):
            pieces.step(n)
        self.assertEqual(pieces.t, whole.t)
        for column, values in whole.trace.items():
            self.assertTrue(np.array_equal(values, pieces.trace[column]), column)
        self.assertTrue(np.array_equal(whole.state["q"], pieces.state["q"]))


class Checkpoints(unittest.TestCase):
    def test_a_resumed_run_ends_bit_for_bit_as_the_run_that_went_on(self):
        scene = beamslider.Scene().set("Excitation/Frequency", 121.0)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "run.ckpt")
            run = beamslider.Run(scene)
            run.advance(0.3)
            run.checkpoint(path)
            run.advance(0.3)
            resumed = beamslider.Run.resume(path)
            self.assertAlmostEqual(resumed.t, 0.3, delta=1e-9)
            self.assertEqual(resumed.scene.get("Excitation/Frequency"), 121.0)
            resumed.advance(0.3)
            self.assertEqual(resumed.t, run.t)
            for name in ("trace", "periods"):
                a, b = getattr(run, name), getattr(resumed, name)
                for column in a:
                    self.assertTrue(np.array_equal(a[column], b[column]), f"{name}.{column}")
            for key in ("q", "u", "slider_velocity"):
                self.assertTrue(np.array_equal(run.state[key], resumed.state[key]), key)

    def test_a_checkpoint_of_a_changed_scene_file_or_a_damaged_one_is_refused(self):
        with tempfile.TemporaryDirectory() as tmp:
            scene_file = os.path.join(tmp, "mine.prm")
            beamslider.Scene().write(scene_file)
            path = os.path.join(tmp, "run.ckpt")
            run = beamslider.Run(scene_file)
            run.advance(0.01)
            run.checkpoint(path)
            with open(path, "rb") as f:
                good = f.read()
            damaged = bytearray(good)
            damaged[len(damaged) // 2] ^= 0xFF
            with open(path, "wb") as f:
                f.write(bytes(damaged))
            with self.assertRaises(ValueError) as raised:
                beamslider.Run.resume(path)
            self.assertIn("checksum", str(raised.exception))
            with open(path, "wb") as f:
                f.write(good)
            beamslider.Scene(scene_file).set("Excitation/Frequency", 130.0).write(scene_file)
            with self.assertRaises(ValueError) as raised:
                beamslider.Run.resume(path)
            self.assertIn("another scene", str(raised.exception))
            self.assertIn("Frequency", str(raised.exception))


class BadInput(unittest.TestCase):
    def test_an_unknown_model_and_an_unstable_step_raise_the_command_lines_message(self):
        with self.assertRaises(ValueError) as raised:
            beamslider.Run(model="modal")
        self.assertIn("'modal' is not one of rom, fe", str(raised.exception))
        scene = beamslider.Scene().set("Time stepping/Time step", 3e-4)
        with self.assertRaises(ValueError) as raised:
            beamslider.Run(scene)
        self.assertIn("'Time stepping/Time step' = 0.0003 s is not allowed", str(raised.exception))
        with self.assertRaises(ValueError):
            beamslider.Run().advance(-1)


class CtrlC(unittest.TestCase):
    def test_sigint_raises_keyboard_interrupt_and_the_run_goes_on_unchanged(self):
        run = beamslider.Run()

        def stop_once_under_way():
            while run.t == 0:  # the property reads the run's time under the GIL
                threading.Event().wait(0.001)
            os.kill(os.getpid(), signal.SIGINT)

        stopper = threading.Thread(target=stop_once_under_way)
        stopper.start()
        with self.assertRaises(KeyboardInterrupt):
            run.advance(600)
        stopper.join()
        stopped_at = run.t
        self.assertGreater(stopped_at, 0)
        self.assertLess(stopped_at, 600)
        # Whole steps only, and the run continues to the same state as one
        # that was never stopped.
        steps = round(stopped_at / run.time_step)
        self.assertAlmostEqual(stopped_at, steps * run.time_step, delta=1e-9)
        end = (steps + 3000) * run.time_step
        run.step(3000)
        whole = beamslider.Run()
        whole.step(steps + 3000)
        self.assertAlmostEqual(run.t, end, delta=1e-9)
        for column, values in whole.trace.items():
            self.assertTrue(np.array_equal(values, run.trace[column]), column)
        self.assertIs(signal.getsignal(signal.SIGINT), signal.default_int_handler)


if __name__ == "__main__":
    unittest.main()
