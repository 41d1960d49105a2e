"""Chart of report section 5.1-5.2, the error ladder (ladder.csv and
ladder_members.csv in the report folder): left, the final slider position
x_C/L of every member of every rung (dots) with the median (bar); right,
speed against accuracy: the stated cost of one member against the
Wasserstein distance W1 of the rung's final positions to the reference, with
its 90 % bootstrap interval as error bar and the ensembles' own spread as a
grey mark. With front.csv (every ladder), the rungs that moved when refined (dt/2, or 1.5 N modes)
are drawn hollow and the speed-accuracy front (by the stated cost) as a line.
Arguments: report folder, scene name."""
import os
import sys
from collections import defaultdict

from plot_common import plt, save_figure, read_rows  # noqa: E402


def main(folder, scene):
    rungs = sorted(read_rows(f"{folder}/ladder.csv"), key=lambda r: int(r["index"]))
    finals = defaultdict(list)
    for r in read_rows(f"{folder}/ladder_members.csv"):
        if r["final_x_over_L"]:
            finals[r["rung"]].append(float(r["final_x_over_L"]))
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.8), gridspec_kw=dict(width_ratios=[1.3, 1]))
    names = [r["rung"] for r in rungs]
    for i, r in enumerate(rungs):
        color = "tab:red" if r["family"] == "fe" else "tab:blue"
        x = finals[r["rung"]]
        ax1.plot([i] * len(x), x, "o", color=color, alpha=0.6, ms=5)
        if r["final_x_median"]:
            ax1.plot([i - 0.3, i + 0.3], [float(r["final_x_median"])] * 2, "-", color="k", lw=2 if r["reference"] == "1" else 1)
    ax1.set_xticks(range(len(names)))
    ax1.set_xticklabels(names, rotation=30, ha="right", fontsize=7)
    ax1.set_ylabel("final slider position $x_C/L$")
    ax1.set_title(f"{scene}: end state per member (bar: median; thick: reference)", fontsize=9)
    ax1.grid(alpha=0.3)

    front = {}
    if os.path.exists(f"{folder}/front.csv"):
        front = {r["rung"]: r for r in read_rows(f"{folder}/front.csv")}
    for r in rungs:
        if r["reference"] == "1":
            ax2.plot(float(r["cost_units"]), 0, "s", color="k")
            ax2.annotate(r["rung"] + " (reference)", (float(r["cost_units"]), 0), fontsize=7, xytext=(-4, 6),
                         textcoords="offset points", ha="right")
            continue
        if not r["w1_to_reference"]:
            continue
        cost, w = float(r["cost_units"]), float(r["w1_to_reference"])
        low, high = float(r["w1_low"]), float(r["w1_high"])
        color = "tab:red" if r["family"] == "fe" else "tab:blue"
        moved = r["rung"] in front and front[r["rung"]]["refined_alike"] == "0"
        ax2.errorbar(cost, w, yerr=[[max(w - low, 0)], [max(high - w, 0)]], fmt="s" if r["family"] == "fe" else "o",
                     color=color, capsize=3, mfc="white" if moved else color)
        ax2.plot(cost, float(r["spread"]), "_", color="grey", ms=12)
        ax2.annotate(r["rung"], (cost, w), fontsize=7, xytext=(4, 4), textcoords="offset points")
    on_front = sorted((float(r["cost_units"]), float(r["w1_to_reference"])) for r in front.values()
                      if r["on_front"] == "1")
    if on_front:
        ax2.plot([c for c, _ in on_front], [w for _, w in on_front], "-", color="tab:green", lw=1.5,
                 label="front (alike refined; hollow: moved when refined)")
        ax2.legend(fontsize=7, loc="upper right")
    ax2.set_xscale("log")
    # W1 spans 1e-4 (converged models) to 0.1 L (the other basin): logarithmic
    # above 1e-4, linear below it, so that the reference's 0 stays on the chart.
    ax2.set_yscale("symlog", linthresh=1e-4)
    ax2.set_ylim(0, 0.3)
    ax2.set_xlabel("cost of one member [units: steps of the published ROM]")
    ax2.set_ylabel("W$_1$ of final $x_C/L$ to the reference")
    ax2.set_title("speed against accuracy (bars: 90 % interval; grey: ensemble spread)", fontsize=9)
    ax2.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    save_figure(fig, f"{folder}/ladder.png", dpi=120)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
