"""The studies as Python objects (beamslider.Ensemble, Sweep, Map): computed
in the process and held in memory, nothing written until save(); their
arrays hold what the command's files hold; save(folder) writes the files the
command writes (compared with a run of the program on the same options,
cell for cell apart from wall times, and the rows of the studies whose runs
go in parallel as sets); the comparison of two Ensemble objects equals the
command's --against; a changed scene file is refused by save. Run by ctest
with PYTHONPATH set to build/python and BEAMSLIDER_EXECUTABLE to the built
program."""

import csv
import os
import subprocess
import tempfile
import unittest

import numpy as np

import beamslider

EXECUTABLE = os.environ["BEAMSLIDER_EXECUTABLE"]
# The scene as a Scene passes it on (its path), so that the records agree.
SCENE = beamslider.Scene("mueller2023").path


def run_cli(folder, command, *args):
    done = subprocess.run([EXECUTABLE, command, SCENE, *args, "--output", folder, "--quiet"],
                          capture_output=True, text=True, timeout=600)
    if done.returncode != 0:
        raise AssertionError(done.stderr)


def csv_rows(path, drop=()):
    """Header and rows of a CSV file, without the columns named in `drop`."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    keep = [i for i, name in enumerate(rows[0]) if name not in drop]
    return [[r[i] for i in keep] for r in rows]


def command_prm(folder):
    with open(os.path.join(folder, "command.prm"), encoding="utf-8") as f:
        return [line for line in f if "output" not in line]


ENSEMBLE = ["--case", "signature-move", "--members", "3", "--end-time", "1.5"]


class EnsembleObject(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.cli = os.path.join(cls.tmp.name, "cli")
        run_cli(cls.cli, "ensemble", *ENSEMBLE)
        cls.lines = []
        cls.ensemble = beamslider.Ensemble("mueller2023", case="signature-move", members=3, end_time=1.5,
                                           progress=cls.lines.append)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_arrays_hold_the_members_csv(self):
        table = beamslider.read_table(os.path.join(self.cli, "members.csv"))
        for column in ("final_x_over_L", "final_amplitude_over_h", "jump_time_s", "turn_x_over_L"):
            written = np.array([float("%.10g" % x) for x in self.ensemble.members[column]])
            self.assertTrue(np.array_equal(written, table[column], equal_nan=True), column)
        self.assertEqual(list(self.ensemble.members["outcome"]), list(table["outcome"]))
        self.assertEqual(list(self.ensemble.members), list(table))  # the same columns, in order
        self.assertEqual(list(self.ensemble.statistics),
                         list(beamslider.read_table(os.path.join(self.cli, "statistics.csv"))))
        periods = beamslider.read_table(os.path.join(self.cli, "member_periods.csv"))
        self.assertEqual(len(periods["t_s"]), len(self.ensemble.member_periods["t_s"]))
        written = np.array([float("%.8g" % x) for x in self.ensemble.member_periods["x_over_L"]])  # 8 digits there
        self.assertTrue(np.array_equal(written, periods["x_over_L"]))
        self.assertTrue(any("ensemble mueller2023" in line for line in self.lines), self.lines[:3])

    def test_save_writes_the_commands_files(self):
        folder = os.path.join(self.tmp.name, "saved")
        result = self.ensemble.save(folder)
        for name in ("members.csv", "member_periods.csv", "statistics.csv"):
            self.assertEqual(csv_rows(os.path.join(folder, name), drop=("wall_s",)),
                             csv_rows(os.path.join(self.cli, name), drop=("wall_s",)), name)
        self.assertEqual(command_prm(folder), command_prm(self.cli))
        with open(os.path.join(folder, "parameters.prm")) as a, open(os.path.join(self.cli, "parameters.prm")) as b:
            self.assertEqual(a.read(), b.read())
        with open(os.path.join(folder, "run.txt")) as f:
            record = f.read()
        self.assertIn(f"beamslider ensemble {SCENE} --model rom --case signature-move --members 3 --end-time 1.5", record)
        self.assertIn("completed (exit 0)", record)
        self.assertEqual(result.tables["members"]["outcome"].tolist(), self.ensemble.members["outcome"].tolist())

    def test_compare_is_the_commands_against(self):
        # Started 0.5e-9 L further: no member is one of the first ensemble's
        # (a tie, which the 10 rounded digits of members.csv would break).
        start = "Initial state/Slider position"
        shifted = beamslider.Scene("mueller2023")
        shifted.set(start, 0.3 + 5e-10)
        other = beamslider.Ensemble(shifted, case="signature-move", members=3, end_time=1.5)
        against = os.path.join(self.tmp.name, "against")
        run_cli(against, "ensemble", *ENSEMBLE, "--set", f"{start}={0.3 + 5e-10!r}", "--against", self.cli)
        written = beamslider.read_table(os.path.join(against, "comparison.csv"))
        mine = other.compare(self.ensemble)
        # --against reads the other ensemble's members.csv, positions rounded
        # to 10 digits (about 1e-11 L): the distances agree to that.
        for column in ("wasserstein", "wasserstein_low", "wasserstein_high", "ks", "own_spread", "median_shift"):
            self.assertTrue(np.allclose(mine[column], written[column], rtol=0, atol=1e-9, equal_nan=True),
                            (column, mine[column] - written[column]))
        self.assertEqual(list(mine), list(written))

    def test_nothing_is_written_until_saved(self):
        with tempfile.TemporaryDirectory() as cwd:
            here = os.getcwd()
            os.chdir(cwd)
            try:
                beamslider.Ensemble("mueller2023", members=2, end_time=0.2)
            finally:
                os.chdir(here)
            self.assertEqual(os.listdir(cwd), [])

    def test_a_changed_scene_file_is_refused_by_save(self):
        with tempfile.TemporaryDirectory() as tmp:
            scene_file = os.path.join(tmp, "mine.prm")
            beamslider.Scene("mueller2023").write(scene_file)
            ensemble = beamslider.Ensemble(scene_file, members=2, end_time=0.2)
            scene = beamslider.Scene(scene_file)
            scene.set("Excitation/Frequency", 120.0)
            scene.write(scene_file)
            with self.assertRaisesRegex(ValueError, "reads differently"):
                ensemble.save(os.path.join(tmp, "out"))

    def test_bad_input_is_a_value_error(self):
        with self.assertRaisesRegex(ValueError, "^error: .*members"):
            beamslider.Ensemble("mueller2023", members=0)


class LadderObject(unittest.TestCase):
    def test_save_writes_the_commands_files(self):
        options = ["--rung", "ROM N=5 (published)", "--members", "2", "--end-time", "0.5"]
        with tempfile.TemporaryDirectory() as tmp:
            run_cli(os.path.join(tmp, "cli"), "ladder", *options)
            ladder = beamslider.Ladder("mueller2023", rung=["ROM N=5 (published)"], members=2, end_time=0.5)
            ladder.save(os.path.join(tmp, "py"))
            wall = ("wall_s", "wall_s_per_member")
            for name in ("ladder.csv", "ladder_members.csv", "ladder_steps.csv", "convergence.csv"):
                self.assertEqual(csv_rows(os.path.join(tmp, "py", name), drop=wall),
                                 csv_rows(os.path.join(tmp, "cli", name), drop=wall), name)
            for table, name in ((ladder.rungs, "ladder.csv"), (ladder.members, "ladder_members.csv")):
                self.assertEqual(list(table), csv_rows(os.path.join(tmp, "cli", name))[0], name)
            written = beamslider.read_table(os.path.join(tmp, "cli", "ladder.csv"))
            self.assertEqual(list(ladder.rungs["rung"]), list(written["rung"]))
            np.testing.assert_allclose(ladder.rungs["final_x_median"], written["final_x_median"], rtol=1e-5)
            self.assertTrue(all(check["converged"] for check in ladder.checks.values() if check["claim"]), ladder.checks)
            # The published ROM at half its step is a finding, not a claim;
            # the front holds only rungs of the ladder, the reference never.
            self.assertFalse(ladder.checks["ROM N=5 (published) in Δt"]["claim"])
            self.assertTrue(set(ladder.front) <= set(ladder.rungs["rung"]) - {ladder.rungs["rung"][-1]}, ladder.front)


class SweepObject(unittest.TestCase):
    def test_save_writes_the_commands_files(self):
        options = dict(from_=0.25, to=0.29, step=0.02, settle_time=0.1, average_time=0.1, free_time=0.3)
        with tempfile.TemporaryDirectory() as tmp:
            run_cli(os.path.join(tmp, "cli"), "sweep", "--from", "0.25", "--to", "0.29", "--step", "0.02",
                    "--settle-time", "0.1", "--average-time", "0.1", "--free-time", "0.3")
            sweep = beamslider.Sweep("mueller2023", **options)
            self.assertEqual(len(sweep.pcs["x_over_L"]), 6)
            self.assertEqual(list(sweep.pcs), csv_rows(os.path.join(tmp, "cli", "pcs.csv"))[0])
            sweep.save(os.path.join(tmp, "py"))
            for name in ("pcs.csv", "runs.csv"):  # the branches' rows interleave as they finish: compared as sets
                a = csv_rows(os.path.join(tmp, "py", name))
                b = csv_rows(os.path.join(tmp, "cli", name))
                self.assertEqual(a[0], b[0])
                self.assertEqual(sorted(a[1:]), sorted(b[1:]), name)
            for name in ("resonance.csv", "free_periods.csv"):
                self.assertEqual(csv_rows(os.path.join(tmp, "py", name)), csv_rows(os.path.join(tmp, "cli", name)))


class MapObject(unittest.TestCase):
    def test_save_writes_the_commands_files(self):
        with tempfile.TemporaryDirectory() as tmp:
            run_cli(os.path.join(tmp, "cli"), "map", "--frequency", "120:124:2", "--end-time", "0.5")
            grid = beamslider.Map("mueller2023", frequency="120:124:2", end_time=0.5)
            self.assertEqual((grid.cells, grid.cells_done), (3, 3))
            self.assertTrue(np.array_equal(np.unique(grid.map["frequency_hz"]), [120.0, 122.0, 124.0]))
            grid.save(os.path.join(tmp, "py"))
            a = csv_rows(os.path.join(tmp, "py", "map.csv"))
            b = csv_rows(os.path.join(tmp, "cli", "map.csv"))
            self.assertEqual(a[0], b[0])
            self.assertEqual(sorted(a[1:]), sorted(b[1:]))  # cells finish in any order
            self.assertEqual(beamslider.read_table(os.path.join(tmp, "py", "map.csv"))["final_x_over_L"].tolist(),
                             [float("%.10g" % x) for x in grid.map["final_x_over_L"]])

    def test_a_stopped_map_keeps_its_cells_and_saves_a_folder_marked_partial(self):
        def stop_after_the_first_cell(line):
            if line.startswith("  cells 1/"):
                beamslider.interrupt()
        with self.assertRaises(beamslider.Interrupted) as raised:
            beamslider.Map("mueller2023", frequency="110:129:1", end_time=0.5, progress=stop_after_the_first_cell)
        partial = raised.exception.result
        self.assertEqual(partial.cells, 20)
        self.assertTrue(1 <= partial.cells_done < 20, partial.cells_done)
        self.assertEqual(len(partial.map["frequency_hz"]), partial.cells_done)
        with tempfile.TemporaryDirectory() as tmp:
            with self.assertWarns(beamslider.PartialResultWarning):
                partial.save(tmp)
            with open(os.path.join(tmp, "run.txt")) as f:
                self.assertIn("the results in this folder are partial", f.read())
            self.assertEqual(len(beamslider.read_table(os.path.join(tmp, "map.csv"))["frequency_hz"]),
                             partial.cells_done)


class BranchesObject(unittest.TestCase):
    """beamslider.Branches runs the study itself (no command line): its
    columns are the command's files' to the last printed digit, and bad
    settings are ValueErrors naming the parameter."""

    def test_columns_are_the_commands_files(self):
        b = beamslider.Branches("mueller2023", from_=0.3, to=0.34, settle_periods=10)
        with tempfile.TemporaryDirectory() as folder:
            run_cli(folder, "branches", "--from", "0.3", "--to", "0.34", "--settle-periods", "10")
            rows = csv_rows(os.path.join(folder, "branches.csv"))
            probes = csv_rows(os.path.join(folder, "attractor.csv"))
        self.assertEqual(len(rows) - 1, len(b.branches["x_over_L"]))
        for i, row in enumerate(rows[1:]):
            self.assertAlmostEqual(float(row[0]), b.branches["x_over_L"][i], delta=1e-9 * abs(float(row[0])))
            self.assertAlmostEqual(float(row[1]), b.branches["amplitude_over_h"][i], delta=1e-9 * float(row[1]))
            self.assertEqual(int(row[3]), int(b.branches["stable"][i]))
        self.assertEqual(len(probes) - 1, len(b.attractor["x_over_L"]))
        for i, row in enumerate(probes[1:]):
            self.assertAlmostEqual(float(row[6]), b.attractor["amplitude_over_h"][i], delta=1e-9 * float(row[6]))

    def test_bad_settings_are_value_errors(self):
        with self.assertRaisesRegex(ValueError, "high x_C/L = 0.3"):
            beamslider.Branches("mueller2023", from_=0.4, to=0.3)
        with self.assertRaisesRegex(ValueError, "settle_periods = -1"):
            beamslider.Branches("mueller2023", settle_periods=-1)
        with self.assertRaisesRegex(ValueError, "probe_step"):
            beamslider.Branches("mueller2023", probe_step="0.1")


if __name__ == "__main__":
    unittest.main()
