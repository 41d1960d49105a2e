"""Charts of `verify --full`, section 5 (report folder as argument):
fe_rom_long.png     the 60 s runs: slider position x_C/L and amplitude envelope
                    (0.1 s mean of ŵ(L/2)/h) against time, FE bold, one figure;
fe_rom_convergence.png  the FE runs of the 5 s window (meshes, time steps, the
                    round-off twin): the same two quantities.
Missing CSV files (a stopped run) are skipped."""
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def read_periods(path):
    periods = defaultdict(list)
    with open(path) as f:
        for r in csv.DictReader(f):
            periods[r["label"]].append((float(r["t_s"]), float(r["slider_x_over_L"]), float(r["amplitude_over_h"])))
    return periods


def envelope(values, span):
    out, total = [], 0.0
    for k, v in enumerate(values):
        total += v
        if k >= span:
            total -= values[k - span]
        out.append(total / min(k + 1, span))
    return out


def two_panel(periods, keep, style, filename, title):
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(10, 7), sharex=True)
    for label, rows in periods.items():
        if not keep(label):
            continue
        t = [r[0] for r in rows]
        span = max(1, round(0.1 / (t[1] - t[0]))) if len(t) > 1 else 1
        s = style(label)
        ax1.plot(t, [r[1] for r in rows], label=label, **s)
        ax2.plot(t, envelope([r[2] for r in rows], span), **s)
    ax1.set_ylabel("slider x_C/L (period mean)")
    ax2.set_ylabel("amplitude ŵ(L/2)/h (0.1 s mean)")
    ax2.set_xlabel("t [s]")
    ax1.set_title(title)
    ax1.legend(fontsize=7, ncol=2)
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(filename, dpi=120)
    plt.close(fig)


def main(folder):
    long_csv = f"{folder}/fe_rom_long_periods.csv"
    if os.path.exists(long_csv):
        def style(label):
            if label.startswith("FE"):
                return dict(color="k", lw=2.0 if "x0+" not in label else 1.0, ls="-" if "x0+" not in label else "--")
            return dict(lw=1.0, ls="-" if "x0+" not in label else ":")
        two_panel(read_periods(long_csv), lambda l: True, style, f"{folder}/fe_rom_long.png",
                  "60 s adaptation: FE (black) against ROM; dashed/dotted: round-off twins (x0+1e-9)")
    short_csv = f"{folder}/fe_rom_periods.csv"
    if os.path.exists(short_csv):
        def style(label):
            return dict(color="k", lw=2.0) if label.startswith("reference") else dict(lw=1.0)
        two_panel(read_periods(short_csv), lambda l: l.startswith("FE") or l.startswith("reference"), style,
                  f"{folder}/fe_rom_convergence.png", "FE convergence: meshes, time steps and the round-off twin")


if __name__ == "__main__":
    main(sys.argv[1])
