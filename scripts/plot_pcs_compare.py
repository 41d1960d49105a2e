"""Two prescribed-position sweeps of one scene side by side (beamslider sweep
--against): pcs_compare.png in the first folder. Top: amplitude of w(L/2)
over h against x_C/L, both branches of both sweeps. Bottom: the
period-averaged horizontal contact force F_x (+ toward x = L) with its 95 %
batch-means interval as error bars, and the zero-crossing intervals of
crossings.csv as shaded spans (stable crossings only).
Arguments: folder, other folder, label, other label."""
import os
import sys

from plot_common import plt, save_figure, read_rows  # noqa: E402


def main(folder, other, label, other_label):
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    styles = {"up": "o", "down": "s"}
    for name, path, colour, line in ((label, folder, "tab:blue", "-"), (other_label, other, "tab:red", "--")):
        rows = read_rows(os.path.join(path, "pcs.csv"), missing_ok=True)
        for direction in ("up", "down"):
            r = sorted((row for row in rows if row["direction"] == direction), key=lambda row: float(row["x_over_L"]))
            if not r:
                continue
            x = [float(row["x_over_L"]) for row in r]
            ax1.plot(x, [float(row["amplitude_over_h"]) for row in r], line, marker=styles[direction], ms=3,
                     color=colour, lw=1, label=f"{name}, {direction}")
            ax2.errorbar(x, [float(row["mean_fx_N"]) for row in r], yerr=[float(row["mean_fx_ci95_N"]) for row in r],
                         fmt=styles[direction], ls=line, ms=3, lw=1, elinewidth=0.6, capsize=2, color=colour,
                         label=f"{name}, {direction}")
    for row in read_rows(os.path.join(folder, "crossings.csv"), missing_ok=True):
        if row["stable"] == "1":
            colour = "tab:blue" if row["sweep"] == "this" else "tab:red"
            ax2.axvspan(float(row["x_low_over_L"]), float(row["x_high_over_L"]), color=colour, alpha=0.15, lw=0)
    ax1.set_ylabel(r"amplitude $\hat w_{L/2}/h$")
    ax1.set_title("Prescribed slider position: two sweeps")
    ax1.legend(fontsize=7)
    ax1.grid(alpha=0.3)
    ax2.axhline(0, color="k", lw=0.6)
    ax2.set_xlabel(r"slider position $x_C/L$")
    ax2.set_ylabel(r"$\bar F_x$ [N] with 95 % interval")
    ax2.legend(fontsize=7)
    ax2.grid(alpha=0.3)
    fig.tight_layout()
    save_figure(fig, os.path.join(folder, "pcs_compare.png"), dpi=120)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4])
