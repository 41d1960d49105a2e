"""Charts for the verification section "FE against ROM" (report folder and the
scene's time step as arguments): fe_rom_traces.png (amplitude and slider
position per excitation period, every model), speed_accuracy.png (error
against wall time, Pareto front marked), explicit_time_step_limit.png."""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main(folder, dt):
    periods = defaultdict(list)
    for r in read(f"{folder}/fe_rom_periods.csv"):
        periods[r["label"]].append(r)
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True)
    for label, rows in periods.items():
        t = [float(r["t_s"]) for r in rows]
        ref = label.startswith("reference")
        if not ref and not ("ROM N=" in label and "analytic dt=" + format(float(dt), "g") in label) and "FE" not in label:
            continue
        style = dict(color="k", lw=2.2) if ref else dict(lw=1)
        ax1.plot(t, [float(r["amplitude_over_h"]) for r in rows], label=label, **style)
        ax2.plot(t, [float(r["slider_x_over_L"]) for r in rows], **style)
    ax1.set_ylabel("amplitude ŵ(L/2)/h per period")
    ax2.set_ylabel("slider x_C/L (period mean)")
    ax2.set_xlabel("t [s]")
    ax1.legend(fontsize=7, ncol=2)
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(f"{folder}/fe_rom_traces.png", dpi=120)

    runs = [r for r in read(f"{folder}/fe_rom_runs.csv") if r["drift_error"]]
    fig, ax = plt.subplots(figsize=(8, 5))
    for r in runs:
        x, y = float(r["wall_seconds"]), max(float(r["drift_error"]), 1e-12)
        marker = "s" if r["family"] == "fe" else "o"
        color = "tab:red" if r["family"] == "fe" else "tab:blue"
        ax.loglog(x, y, marker, color=color, ms=7 if r["pareto"] == "1" else 5,
                  mfc=color if r["pareto"] == "1" else "none")
        ax.annotate(r["label"], (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points")
    front = sorted([r for r in runs if r["pareto"] == "1"], key=lambda r: float(r["wall_seconds"]))
    ax.loglog([float(r["wall_seconds"]) for r in front], [max(float(r["drift_error"]), 1e-12) for r in front],
              "k--", lw=1, label="Pareto front (filled)")
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("slider drift error against the reference")
    ax.set_title("speed against accuracy (squares FE, circles ROM)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{folder}/speed_accuracy.png", dpi=120)

    rows = read(f"{folder}/explicit_time_step_limit.csv")
    n = [int(r["n_modes"]) for r in rows]
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    ax.semilogy(n, [float(r["stable_limit_s"]) for r in rows], "o-", label="stability limit 2/ω_N")
    ax.semilogy(n, [float(r["seed_rule_s"]) for r in rows], "s--", label="seed rule 2π/(5ω_N)")
    ax.axhline(float(dt), color="r", ls=":", label=f"scene Δt = {float(dt):g} s")
    ax.set_xlabel("modes N")
    ax.set_ylabel("time step [s]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(f"{folder}/explicit_time_step_limit.png", dpi=120)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
