"""Chart of a free-slider run (like seed Figs. 5-8): trace.png in the given
folder, from trace.csv (and periods.csv for the amplitude envelope).
Arguments: folder, title, beam thickness h [m].
Top: beam deflection at L/2 relative to the base, over h (black), and the
per-period amplitude (grey). Bottom: slider position x_C/L (red).

A 60 s run has 60 000 trace rows, more than a 990-pixel-wide chart can show:
the deflection is drawn as its minimum and maximum over each of
`plot_columns` time bins (the envelope a full line would paint), the slider
position at the bins' starts. The CSV keeps every row.

beamslider starts this script with --arguments-from-stdin before the run, so
that importing matplotlib (about 0.35 s) overlaps the computation; the real
arguments then arrive on standard input, NUL-separated, once the CSV files
are complete. No input means the run ended without a chart to draw."""
import os
import sys

from plot_common import plt, save_figure  # noqa: E402
import numpy as np

plot_columns = 2000


def arguments():
    if sys.argv[1:2] != ["--arguments-from-stdin"]:
        return sys.argv[1:]
    data = sys.stdin.buffer.read()
    if not data:
        sys.exit(0)
    return [a.decode("utf-8", "surrogateescape") for a in data.split(b"\0")[:-1]]


def read_columns(path, names):
    """The named columns of a CSV file as float arrays (empty if the file has no rows)."""
    if not os.path.exists(path):
        return {n: np.empty(0) for n in names}
    with open(path) as f:
        header = f.readline().strip().split(",")
        if not f.readline().strip():  # no row: a run that ended before its first period
            return {n: np.empty(0) for n in names}
    index = [header.index(n) for n in names]
    data = np.loadtxt(path, delimiter=",", skiprows=1, usecols=index, ndmin=2)
    return {n: data[:, k] for k, n in enumerate(names)}


def envelope(t, y, bins):
    """(t, y) reduced to min and max of y over `bins` equal row ranges, as a
    zig-zag line that paints the same band as the full signal."""
    if len(t) <= 2 * bins:
        return t, y
    edges = np.linspace(0, len(t), bins + 1).astype(int)
    low = np.minimum.reduceat(y, edges[:-1])
    high = np.maximum.reduceat(y, edges[:-1])
    return np.repeat(t[edges[:-1]], 2), np.column_stack([low, high]).ravel()


def main(folder, title, h):
    trace = read_columns(os.path.join(folder, "trace.csv"), ["t_s", "slider_x_over_L", "w_center_m"])
    periods = read_columns(os.path.join(folder, "periods.csv"), ["t_end_s", "amplitude_over_h"])
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True, gridspec_kw={"height_ratios": [3, 2]})
    with np.errstate(divide="ignore", invalid="ignore"):  # a run that failed may hold nan
        t_w, w = envelope(trace["t_s"], trace["w_center_m"] / h, plot_columns)
    ax1.plot(t_w, w, color="k", lw=0.3, label=r"$w(L/2)/h$")
    t_p, a = envelope(periods["t_end_s"], periods["amplitude_over_h"], plot_columns)
    ax1.plot(t_p, a, color="tab:grey", lw=1.0, label="amplitude per period")
    ax1.set_ylabel(r"$w(L/2)/h$")
    ax1.set_title(title)
    ax1.legend(loc="upper left", fontsize=8)
    ax1.grid(alpha=0.3)
    n = len(trace["t_s"])
    rows = np.unique(np.r_[0:n:max(1, n // plot_columns), max(n - 1, 0)]) if n else []
    ax2.plot(trace["t_s"][rows], trace["slider_x_over_L"][rows], color="tab:red", lw=1.0)
    ax2.axhline(0.5, color="k", lw=0.5, ls=":")
    ax2.set_ylabel(r"slider $x_C/L$")
    ax2.set_xlabel("t [s]")
    ax2.grid(alpha=0.3)
    fig.tight_layout()
    save_figure(fig, os.path.join(folder, "trace.png"), dpi=110)


if __name__ == "__main__":
    args = arguments()
    main(args[0], args[1] if len(args) > 1 else "", float(args[2]) if len(args) > 2 else 1e-3)
