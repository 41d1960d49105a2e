"""Chart of a prescribed-slider-position sweep (seed Figs. 10b and 14):
pcs.png in the given folder, from pcs.csv, resonance.csv and (if present)
free_periods.csv. Top: amplitude of w(L/2) over h against x_C/L, both sweep
branches, the Eq. 5 resonance curve and the free slider. Bottom: the
period-averaged horizontal contact force on the slider (+ toward x = L), with
its spread over the averaged periods."""
import os
import sys

from plot_common import plt, save_figure, read_rows  # noqa: E402


def main(folder, scene):
    pcs = read_rows(os.path.join(folder, "pcs.csv"), missing_ok=True)
    resonance = read_rows(os.path.join(folder, "resonance.csv"), missing_ok=True)
    free = read_rows(os.path.join(folder, "free_periods.csv"), missing_ok=True)
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    colours = {"up": "tab:orange", "down": "tab:green"}
    labels = {"up": "prescribed, $x_C$ increasing", "down": "prescribed, $x_C$ decreasing"}
    for direction in ("up", "down"):
        rows = [r for r in pcs if r["direction"] == direction]
        if not rows:
            continue
        x = [float(r["x_over_L"]) for r in rows]
        a = [float(r["amplitude_over_h"]) for r in rows]
        f = [float(r["mean_fx_N"]) for r in rows]
        fs = [float(r["mean_fx_std_N"]) for r in rows]
        ax1.plot(x, a, "o-", ms=3, color=colours[direction], label=labels[direction])
        ax2.errorbar(x, f, yerr=fs, fmt="o-", ms=3, lw=1, elinewidth=0.5, color=colours[direction],
                     label=labels[direction])
    rx = [float(r["x_over_L"]) for r in resonance if r["amplitude_over_h"]]
    ra = [float(r["amplitude_over_h"]) for r in resonance if r["amplitude_over_h"]]
    if rx:
        ax1.plot(rx, ra, "--", color="grey", label="resonance curve (seed Eq. 5)")
    if free:
        ax1.plot([float(r["slider_x_over_L"]) for r in free], [float(r["amplitude_over_h"]) for r in free], "-",
                 color="k", lw=0.6, label="free slider (one point per period)")
    top = max([float(r["amplitude_over_h"]) for r in pcs] + [float(r["amplitude_over_h"]) for r in free] + [0.1])
    ax1.set_ylim(0, 1.15 * top)
    ax1.set_ylabel(r"amplitude $\hat w_{L/2}/h$")
    ax1.set_title(f"Prescribed slider position: scene {scene}")
    ax1.legend(fontsize=8)
    ax1.grid(alpha=0.3)
    ax2.axhline(0, color="k", lw=0.6)
    ax2.set_xlabel(r"slider position $x_C/L$")
    ax2.set_ylabel(r"$\bar F_x$ [N] (+ toward $x = L$)")
    ax2.grid(alpha=0.3)
    fig.tight_layout()
    save_figure(fig, os.path.join(folder, "pcs.png"), dpi=120)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "")
