"""A chart belongs to the run that started it (scripts/plot_common.py,
issue 74): killed with it, so that a run killed with kill -9 while its
chart is drawn leaves no writer behind in a folder the next run may take,
and never started once its run is gone. The "run" here is a process that
starts a chart the way beamslider does (BEAMSLIDER_PARENT_PID in the
environment: runtime/child_process.cc) and is then killed."""
import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest

SCRIPTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts")
# A chart that imports plot_common as every chart does, says it is ready
# and would then draw for ten minutes.
CHART = ("import sys, time; sys.path.insert(0, sys.argv[1]); import plot_common; "
         "open(sys.argv[2], 'w').close(); time.sleep(600)")


def gone(pid):
    """The process has ended (or is a zombie nobody reaped yet)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] == "Z"
    except FileNotFoundError:
        return True


def wait_until(condition, seconds):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if condition():
            return True
        time.sleep(0.05)
    return condition()


class ChartsDieWithTheirRun(unittest.TestCase):
    def test_a_chart_whose_run_is_killed_ends_with_it(self):
        with tempfile.TemporaryDirectory() as tmp:
            ready, pid_file = os.path.join(tmp, "ready"), os.path.join(tmp, "chart.pid")
            # The run: it starts the chart with its own pid as the parent's,
            # then becomes a process that would outlive any chart (exec sleep).
            run = subprocess.Popen(["sh", "-c", 'BEAMSLIDER_PARENT_PID=$$ "$0" -c "$1" "$2" "$3" & echo $! > "$4"; '
                                    'exec sleep 600', sys.executable, CHART, SCRIPTS, ready, pid_file])
            try:
                self.assertTrue(wait_until(lambda: os.path.exists(ready), 120), "the chart did not start")
                with open(pid_file) as f:
                    chart = int(f.read())
                self.assertFalse(gone(chart))
            finally:
                run.send_signal(signal.SIGKILL)
                run.wait()
            # The kernel's parent-death signal is immediate; the bound only
            # keeps a broken build from hanging the suite.
            self.assertTrue(wait_until(lambda: gone(chart), 60), "the chart outlived its killed run")

    def test_a_chart_whose_run_is_gone_does_not_start(self):
        environment = dict(os.environ, BEAMSLIDER_PARENT_PID=str(os.getpid() + 1))
        done = subprocess.run([sys.executable, "-c", "import sys; sys.path.insert(0, sys.argv[1]); "
                               "import plot_common; print('drawn')", SCRIPTS],
                              env=environment, capture_output=True, text=True, timeout=120)
        self.assertEqual(done.returncode, 1, done.stderr)
        self.assertNotIn("drawn", done.stdout)

    def test_a_chart_run_by_hand_is_not_affected(self):
        environment = {k: v for k, v in os.environ.items() if k != "BEAMSLIDER_PARENT_PID"}
        done = subprocess.run([sys.executable, "-c", "import sys; sys.path.insert(0, sys.argv[1]); "
                               "import plot_common; print('drawn')", SCRIPTS],
                              env=environment, capture_output=True, text=True, timeout=120)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("drawn", done.stdout)


if __name__ == "__main__":
    unittest.main()
