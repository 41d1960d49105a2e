"""Chart of a free-slider run (like seed Figs. 5-8): trace.png in the given
folder, from trace.csv (and periods.csv for the amplitude envelope).
Arguments: folder, title, beam thickness h [m].
Top: beam deflection at L/2 relative to the base, over h (black), and the
per-period amplitude (grey). Bottom: slider position x_C/L (red)."""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def columns(path, names):
    out = {n: [] for n in names}
    if not os.path.exists(path):
        return out
    with open(path) as f:
        for row in csv.DictReader(f):
            for n in names:
                out[n].append(float(row[n]))
    return out


def main(folder, title, h):
    trace = columns(os.path.join(folder, "trace.csv"), ["t_s", "slider_x_over_L", "w_center_m"])
    periods = columns(os.path.join(folder, "periods.csv"), ["t_end_s", "amplitude_over_h"])
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True, gridspec_kw={"height_ratios": [3, 2]})
    ax1.plot(trace["t_s"], [w / h for w in trace["w_center_m"]], color="k", lw=0.3, label=r"$w(L/2)/h$")
    ax1.plot(periods["t_end_s"], periods["amplitude_over_h"], color="tab:grey", lw=1.0,
             label="amplitude per period")
    ax1.set_ylabel(r"$w(L/2)/h$")
    ax1.set_title(title)
    ax1.legend(loc="upper left", fontsize=8)
    ax1.grid(alpha=0.3)
    ax2.plot(trace["t_s"], trace["slider_x_over_L"], color="tab:red", lw=1.0)
    ax2.axhline(0.5, color="k", lw=0.5, ls=":")
    ax2.set_ylabel(r"slider $x_C/L$")
    ax2.set_xlabel("t [s]")
    ax2.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "trace.png"), dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "", float(sys.argv[3]) if len(sys.argv) > 3 else 1e-3)
