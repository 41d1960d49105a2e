"""What beamslider's plot scripts share: matplotlib without a display,
reading a CSV file written by beamslider into one dict per row, and saving a
chart whole (save_figure) as every result file is written.

Import it first (`from plot_common import plt, read_rows`): it selects the
Agg backend before pyplot is loaded. The scripts live beside it and are run
as `python3 scripts/NAME.py`, so it is found on the script's own path."""
import csv
import math
import os
import signal
import sys


def _die_with_the_run():
    """A chart belongs to the run that started it (BEAMSLIDER_PARENT_PID):
    the kernel kills it when that run ends (Linux's parent-death signal),
    so a run killed while its chart is drawn leaves no writer behind in a
    folder the next run may take; a chart whose run is gone already does
    not start. Run by hand (no such variable), nothing changes."""
    parent = os.environ.get("BEAMSLIDER_PARENT_PID")
    if not parent:
        return
    try:
        import ctypes
        PR_SET_PDEATHSIG = 1
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
    except (OSError, AttributeError):
        pass  # not Linux: the check below still stops a late start
    if os.getppid() != int(parent):
        os._exit(1)


_die_with_the_run()

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend choice)

__all__ = ["plt", "read_rows", "positive_number", "read_checked_rows", "save_figure"]


def save_figure(fig, path, **options):
    """fig.savefig(path, **options), whole: into a hidden temporary file
    beside `path`, renamed over it once complete, so that a reader never sees
    half a chart and a link at `path` is replaced, never written through
    (doc/cli.md, "A run's folder belongs to one run")."""
    folder, name = os.path.split(path)
    temporary = os.path.join(folder, f".{name}.{os.getpid()}.tmp")
    options.setdefault("format", os.path.splitext(name)[1][1:] or "png")
    try:
        fig.savefig(temporary, **options)
        os.replace(temporary, path)
    except BaseException:
        if os.path.lexists(temporary):
            os.unlink(temporary)
        raise


def read_rows(path, missing_ok=False):
    """The rows of a CSV file with a header line, as dicts of strings.
    With missing_ok, a file that does not exist gives no rows (a sweep that
    was not run); otherwise it is an error."""
    if missing_ok and not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def positive_number(text, what, script):
    """float(text) if it is finite and > 0; else the script exits naming
    `what` (e.g. "file line 3, wall_s") and the text."""
    try:
        v = float(text)
    except ValueError:
        v = math.nan
    if not (math.isfinite(v) and v > 0):
        sys.exit(f"{script}: {what}: '{text}' is not a positive number")
    return v


def read_checked_rows(path, columns, script):
    """(line number, row) for each row of a CSV file that has every one of
    `columns` and a value in each; the script exits naming the file, the line
    and what is wrong otherwise, and for a file without rows."""
    try:
        f = open(path, newline="")
    except OSError as e:
        sys.exit(f"{script}: cannot read '{path}': {e.strerror}")
    with f:
        reader = csv.DictReader(f)
        missing = [c for c in columns if c not in (reader.fieldnames or [])]
        if missing:
            sys.exit(f"{script}: {path} lacks the column(s) {', '.join(missing)}")
        rows = []
        for line, row in enumerate(reader, start=2):
            if any(row.get(c) is None for c in columns):
                sys.exit(f"{script}: {path} line {line}: expected {len(reader.fieldnames)} fields")
            rows.append((line, row))
    if not rows:
        sys.exit(f"{script}: {path} holds no rows")
    return rows
