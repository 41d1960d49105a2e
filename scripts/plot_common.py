"""What beamslider's plot scripts share: matplotlib without a display, and
reading a CSV file written by beamslider into one dict per row.

Import it first (`from plot_common import plt, read_rows`): it selects the
Agg backend before pyplot is loaded. The scripts live beside it and are run
as `python3 scripts/NAME.py`, so it is found on the script's own path."""
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend choice)

__all__ = ["plt", "read_rows"]


def read_rows(path, missing_ok=False):
    """The rows of a CSV file with a header line, as dicts of strings.
    With missing_ok, a file that does not exist gives no rows (a sweep that
    was not run); otherwise it is an error."""
    if missing_ok and not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))
