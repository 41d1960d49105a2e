"""The objects of the Python module. beamslider.Run, the run held in the
Python process: its trace and periods are the command line's `simulate`
files to the last written digit (ROM and FE); a checkpoint resumes bit for
bit; steps in pieces equal one advance; Ctrl-C raises KeyboardInterrupt and
the run goes on as if never stopped; bad input and foreign checkpoints raise
ValueError with the reason. FEBeam: its modes are the command `modes`' and
SciPy's eigsh on its matrices; its tangent is the derivative of its force.
ReducedModel: its tensor is coefficients.csv's; its force is that tensor's
polynomial. Run by ctest with PYTHONPATH set to build/python and
BEAMSLIDER_EXECUTABLE to the built program."""

import csv
import math
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
    run_cli(folder, "simulate", *args)


def run_cli(folder, command, *args):
    done = subprocess.run([EXECUTABLE, command, "mueller2023", *args, "--output", folder, "--quiet"],
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


    def test_contact_impulses_carry_the_slider(self):
        # Over 2000 steps of the rattling slider, the vertical impulses the
        # corners give it (upper corners push up, lower ones down) are its
        # weight's impulse plus its change of vertical momentum.
        run = beamslider.Run()
        run.advance(0.5)
        scene = beamslider.Scene()
        mass, g = scene.get("Slider/Mass"), scene.get("Contact/Gravity")
        before = run.state["slider_velocity"][1]
        upward = 0.0
        for _ in range(2000):
            run.step(1)
            impulses = run.state["contact_impulses"]
            upward += impulses[0, 0] + impulses[1, 0] - impulses[2, 0] - impulses[3, 0]
            self.assertTrue(np.array_equal(run.state["corners_in_contact"], impulses[:, 0] > 0))
        change = mass * (run.state["slider_velocity"][1] - before)
        expected = mass * g * 2000 * run.time_step + change
        self.assertLess(abs(upward - expected), 0.01 * expected, (upward, expected))  # measured 1e-4


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


    def test_a_failed_runs_checkpoint_resumes_as_the_failed_run(self):
        # The run leaves the physical states at its first step; resumed, it
        # says so, and a step neither advances nor says "completed".
        scene = beamslider.Scene().set("Contact/Gravity", 1e30)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "failed.ckpt")
            run = beamslider.Run(scene)
            with self.assertRaises(RuntimeError):
                run.advance(0.01)
            self.assertEqual(run.status, "unphysical_state")
            run.checkpoint(path)
            resumed = beamslider.Run.resume(path)
            self.assertEqual(resumed.status, "unphysical_state")
            with self.assertRaises(RuntimeError) as raised:
                resumed.step(100)
            self.assertIn("unphysical_state", str(raised.exception))
            self.assertEqual(resumed.t, run.t)


    def test_a_checkpoint_that_is_a_fifo_a_device_or_cut_short_is_refused_naming_it(self):
        # Through the program's one guarded reader: a FIFO or a device is
        # refused by its type before it is opened (a read never waits for a
        # writer), a file cut short by its length and checksum.
        with tempfile.TemporaryDirectory() as tmp:
            sound = os.path.join(tmp, "sound.ckpt")
            run = beamslider.Run(beamslider.Scene())
            run.advance(0.01)
            run.checkpoint(sound)
            with open(sound, "rb") as f:
                good = f.read()
            fifo, device, cut = (os.path.join(tmp, name) for name in ("fifo.ckpt", "device.ckpt", "cut.ckpt"))
            os.mkfifo(fifo)
            os.symlink("/dev/zero", device)
            with open(cut, "wb") as f:
                f.write(good[: len(good) * 3 // 5])
            for path, why in ((fifo, "not a regular file"), (device, "not a regular file"), (cut, cut)):
                with self.assertRaises(ValueError) as raised:
                    beamslider.Run.resume(path)
                self.assertIn(os.path.basename(path), str(raised.exception))
                self.assertIn(why, str(raised.exception))

class BadInput(unittest.TestCase):
    def test_every_bad_argument_is_a_value_error_naming_it_and_its_range(self):
        cases = [(lambda: beamslider.FEBeam(elements=10 ** 8), "elements = 100000000", "[1, 4096]"),
                 (lambda: beamslider.FEBeam(elements=2.5), "elements = 2.5", "[1, 4096]"),
                 (lambda: beamslider.ReducedModel(modes=1000), "modes = 1000", "[1, 40]"),
                 (lambda: beamslider.Run().advance(math.inf), "seconds = inf", "[0, inf)"),
                 (lambda: beamslider.Run().advance(1e9), "seconds = 1000000000.0", "1e11"),
                 (lambda: beamslider.Run().step(-1), "n = -1", "[0, 100000000000]"),
                 (lambda: beamslider.Run().step(True), "n = True", "[0, 100000000000]"),
                 (lambda: beamslider.Ensemble(members=False), "members = False", "give a number")]
        for make, named, allowed in cases:
            with self.assertRaises(ValueError, msg=named) as raised:
                make()
            self.assertIn(named, str(raised.exception))
            self.assertIn(allowed, str(raised.exception))


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

    def test_an_interrupt_with_no_command_running_stops_nothing_later(self):
        beamslider.interrupt()  # no command runs: nothing to stop, nothing kept
        run = beamslider.Run()
        self.assertEqual(run.advance(0.05), "completed")
        self.assertAlmostEqual(run.t, 0.05, delta=1e-9)
        self.assertEqual(beamslider.simulate(end_time=0.05).status, "completed")


class FEBeamMatrices(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.beam = beamslider.FEBeam()
        cls.frequencies, cls.shapes = cls.beam.modes(7)

    def test_modes_are_the_modes_command_and_scipys_eigsh_on_the_matrices(self):
        import scipy.sparse.linalg
        with tempfile.TemporaryDirectory() as tmp:
            run_cli(tmp, "modes", "--modes", "7")
            header, rows = csv_rows(os.path.join(tmp, "modes.csv"))
            column = header.index("frequency_hz")
            cli = np.array([float(r[column]) for r in rows])
        np.testing.assert_allclose(self.frequencies, cli, rtol=1e-9)
        free = self.beam.free_dofs()
        K = self.beam.stiffness()[free][:, free]
        M = self.beam.mass()[free][:, free]
        self.assertLess(abs(K - K.T).max(), 1e-9 * abs(K).max())
        eigenvalues = np.sort(scipy.sparse.linalg.eigsh(K.tocsc(), k=7, M=M.tocsc(), sigma=0,
                                                        return_eigenvectors=False))
        np.testing.assert_allclose(np.sqrt(eigenvalues) / (2 * np.pi), self.frequencies, rtol=1e-9)
        # Mass-normalised shapes.
        phi = self.shapes
        np.testing.assert_allclose(phi.T @ (self.beam.mass() @ phi), np.eye(7), atol=1e-9)

    def test_the_tangent_is_the_derivative_of_the_internal_force(self):
        q = 0.5 * self.beam.scene.get("Beam/Thickness") * self.shapes[:, 0] / abs(self.shapes[:, 0]).max()
        K = self.beam.tangent(q)
        rng = np.random.default_rng(7)
        direction = rng.standard_normal(self.beam.n_dofs) * abs(q).max()
        h = 1e-4
        difference = (self.beam.internal_force(q + h * direction) - self.beam.internal_force(q - h * direction)) / (2 * h)
        exact = K @ direction
        self.assertLess(np.linalg.norm(difference - exact), 1e-6 * np.linalg.norm(exact))
        # At this amplitude the nonlinearity is there to be checked.
        linear = self.beam.stiffness() @ direction
        self.assertGreater(np.linalg.norm(exact - linear), 1e-4 * np.linalg.norm(exact))


    def test_statics_is_the_commands_load_path_and_in_equilibrium(self):
        path = self.beam.statics(line_load=400.0, steps=3)
        with tempfile.TemporaryDirectory() as tmp:
            run_cli(tmp, "statics", "--line-load", "400", "--steps", "3")
            written = beamslider.read_table(os.path.join(tmp, "statics.csv"))
        for column in ("line_load_n_per_m", "w_mid_m", "newton_iterations"):
            np.testing.assert_allclose(path[column], written[column], rtol=1e-9, err_msg=column)
        # The load is λ F at every step: the internal force over λ is the same
        # vector on the bending DoFs, although the response is not linear.
        free = self.beam.free_dofs()
        forces = [self.beam.internal_force(path["displacement"][:, k])[free] / (k + 1) for k in range(3)]
        self.assertLess(np.linalg.norm(forces[2] - forces[0]), 1e-6 * np.linalg.norm(forces[0]))
        w = path["w_mid_m"]
        self.assertTrue(w[2] < 0 and abs(w[2]) < 0.9 * 3 * abs(w[0]))  # down, and stiffening (measured 2.19)


class ReducedModelCoefficients(unittest.TestCase):
    def check_tensor(self, method):
        rom = beamslider.ReducedModel(coefficients=method)
        with tempfile.TemporaryDirectory() as tmp:
            run_cli(tmp, "coefficients", "--method", method)
            expected = beamslider.CoefficientsResult(tmp, keep=False).tensor
        self.assertEqual(rom.coefficients.shape, expected.shape)
        self.assertTrue(np.array_equal(rom.coefficients, expected), method)
        return rom

    def test_the_tensor_is_coefficients_csvs_and_the_force_its_polynomial(self):
        rom = self.check_tensor("analytic")
        q = np.array([2e-4, -1e-4, 5e-5, 3e-5, -2e-5])
        polynomial = np.einsum("njkl,j,k,l->n", rom.coefficients, q, q, q)
        np.testing.assert_allclose(rom.force(q), polynomial, rtol=1e-10, atol=1e-14 * abs(polynomial).max())
        h = 1e-7
        numeric = np.column_stack([(rom.force(q + h * e) - rom.force(q - h * e)) / (2 * h) for e in np.eye(5)])
        np.testing.assert_allclose(rom.tangent(q), numeric, rtol=1e-5, atol=1e-6 * abs(numeric).max())
        fe_frequencies, _ = beamslider.FEBeam().modes(5)
        np.testing.assert_allclose(rom.omega / (2 * np.pi), fe_frequencies, rtol=1e-12)

    def test_step_condensed_tensor_is_coefficients_csvs(self):
        self.check_tensor("step-condensed")

    def test_the_backbone_is_the_backbone_commands(self):
        backbone = beamslider.ReducedModel().backbone(harmonics=5, max_amplitude_over_h=2.0)
        self.assertTrue(backbone["completed"], backbone["message"])
        with tempfile.TemporaryDirectory() as tmp:
            run_cli(tmp, "backbone", "--harmonics", "5", "--max-amplitude", "2")
            header, rows = csv_rows(os.path.join(tmp, "backbone.csv"))
        for name in ("amplitude_over_h", "frequency_hz"):
            column = header.index(name)
            self.assertEqual(["%.10g" % x for x in backbone[name]], [r[column] for r in rows], name)
        # Hardening: the frequency grows with the amplitude.
        self.assertGreater(backbone["frequency_hz"][-1], backbone["frequency_hz"][0])

    def test_shapes_slopes_are_the_derivative_of_the_shapes(self):
        rom = beamslider.ReducedModel()
        x = np.linspace(0.05, 0.95, 13) * rom.length
        h = 1e-6 * rom.length
        phi, dphi = rom.shapes(x)
        numeric = (rom.shapes(x + h)[0] - rom.shapes(x - h)[0]) / (2 * h)
        np.testing.assert_allclose(dphi, numeric, rtol=1e-5, atol=1e-6 * abs(dphi).max())
        with self.assertRaises(ValueError):
            rom.shapes([2 * rom.length])


class SolidObject(unittest.TestCase):
    def test_modes_and_coefficients_are_the_commands_on_the_solid_scene(self):
        solid = beamslider.Solid("mueller2023-solid")
        self.assertEqual(solid.dimension, 3 if solid.scene.get("Solid/Continuum") == "3d" else 2)
        modes = solid.modes(3)
        coefficients = solid.coefficients("exact", 3)
        with tempfile.TemporaryDirectory() as tmp:
            done = subprocess.run([EXECUTABLE, "modes", "mueller2023-solid", "--modes", "3", "--output", tmp, "--quiet"],
                                  capture_output=True, text=True, timeout=600)
            self.assertEqual(done.returncode, 0, done.stderr)
            header, rows = csv_rows(os.path.join(tmp, "modes.csv"))
            column = header.index("frequency_hz")
            cli = np.array([float(r[column]) for r in rows])
        np.testing.assert_allclose(modes["frequency_hz"][:len(cli)], cli, rtol=1e-9)
        self.assertEqual(len(modes["bending"]), 3)
        with tempfile.TemporaryDirectory() as tmp:
            done = subprocess.run([EXECUTABLE, "coefficients", "mueller2023-solid", "--method", "exact", "--modes", "3",
                                   "--output", tmp, "--quiet"], capture_output=True, text=True, timeout=600)
            self.assertEqual(done.returncode, 0, done.stderr)
            expected = beamslider.CoefficientsResult(tmp, keep=False).tensor
        np.testing.assert_allclose(coefficients, expected, rtol=1e-9, atol=1e-9 * abs(expected).max())
        with self.assertRaises(ValueError) as raised:
            beamslider.Solid("mueller2023")
        self.assertIn("no solid", str(raised.exception))

    def test_statics_is_the_commands_load_path(self):
        solid = beamslider.Solid("mueller2023-solid")
        path = solid.statics(line_load=200.0, steps=3)
        with tempfile.TemporaryDirectory() as tmp:
            done = subprocess.run([EXECUTABLE, "statics", "mueller2023-solid", "--line-load", "200", "--steps", "3",
                                   "--output", tmp, "--quiet"], capture_output=True, text=True, timeout=600)
            self.assertEqual(done.returncode, 0, done.stderr)
            written = beamslider.read_table(os.path.join(tmp, "statics.csv"))
        for column in ("line_load_n_per_m", "w_mid_m", "newton_iterations"):
            np.testing.assert_allclose(path[column], written[column], rtol=1e-9, err_msg=column)
        self.assertTrue(np.all(path["w_mid_m"] < 0))  # a downward load bends the strip down
        with self.assertRaisesRegex(ValueError, "steps = 0"):
            solid.statics(line_load=200.0, steps=0)


if __name__ == "__main__":
    unittest.main()
