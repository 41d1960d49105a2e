"""What the FE's time step buys: the end state of the midpoint-rule FE rungs
of a full error ladder (FE Δt, Δt/2, Δt/4, Δt/8, θ = ½; the same model, only
the step differs) against the step and against the wall time per member,
with the members' range, the published ROM and the reference (the scene's FE
model, θ = 0.51 at Δt/2 on mueller2023) marked at its own step and cost. Prints
the successive changes of the median and the orders they imply
(p = log2(|d_k| / |d_k+1|)), and writes timestep_study.csv and
timestep_study.png beside ladder.csv.

    python3 scripts/plot_timestep_study.py reports/mueller2023-full/diagnostics
"""
import math
import os
import sys

from plot_common import plt, save_figure, read_rows

folder = sys.argv[1]
rows = read_rows(os.path.join(folder, "ladder.csv"))
fe = [r for r in rows if r["rung"] in ("FE Δt", "FE Δt/2", "FE Δt/4", "FE Δt/8")]
fe.sort(key=lambda r: -float(r["time_step_s"]))
if len(fe) < 3:
    sys.exit(f"{folder}/ladder.csv has {len(fe)} of the FE Δt rungs: run the ladder with its diagnostic rungs (verify --full --diagnostics)")
published = next(r for r in rows if "published" in r["rung"])
reference = next(r for r in rows if r["reference"] == "1")

dt = [float(r["time_step_s"]) for r in fe]
median = [float(r["final_x_median"]) for r in fe]
low = [float(r["final_x_min"]) for r in fe]
high = [float(r["final_x_max"]) for r in fe]
wall = [float(r["wall_s_per_member"]) for r in fe]

changes = [median[k + 1] - median[k] for k in range(len(median) - 1)]
orders = [math.log2(abs(changes[k]) / abs(changes[k + 1])) if changes[k + 1] != 0 and changes[k] != 0 else float("nan")
          for k in range(len(changes) - 1)]
with open(os.path.join(folder, "timestep_study.csv"), "w") as out:
    out.write("time_step_s,members,final_x_median,final_x_min,final_x_max,wall_s_per_member,change_from_previous\n")
    for k, r in enumerate(fe):
        change = f"{changes[k - 1]:.6g}" if k > 0 else ""
        out.write(f"{dt[k]:.6g},{r['members']},{median[k]:.6g},{low[k]:.6g},{high[k]:.6g},{wall[k]:.6g},{change}\n")
for k, c in enumerate(changes):
    print(f"Δt {dt[k]:.3g} → {dt[k + 1]:.3g} s: median x_C/L {median[k]:.4f} → {median[k + 1]:.4f} ({c:+.4f})")
for k, p in enumerate(orders):
    print(f"observed order from the changes at {dt[k]:.3g} and {dt[k + 1]:.3g} s: {p:.2f}")

figure, (by_step, by_wall) = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
for axes, x, label in ((by_step, dt, "FE time step Δt [s]"), (by_wall, wall, "wall time per member [s]")):
    axes.errorbar(x, median, yerr=[[m - l for m, l in zip(median, low)], [h - m for m, h in zip(median, high)]],
                  fmt="o-", capsize=3, label="FE, midpoint rule θ = ½ (median, members' range)")
    ref_x = float(reference["time_step_s"]) if axes is by_step else float(reference["wall_s_per_member"])
    ref_median = float(reference["final_x_median"])
    axes.errorbar([ref_x], [ref_median],
                  yerr=[[ref_median - float(reference["final_x_min"])], [float(reference["final_x_max"]) - ref_median]],
                  fmt="s", color="C2", capsize=3, label=f"reference: {reference['rung']}")
    axes.axhspan(float(reference["final_x_min"]), float(reference["final_x_max"]), color="C2", alpha=0.2,
                 label=f"reference ({reference['rung']}) range")
    axes.axhline(float(published["final_x_median"]), color="C3", ls="--", label="published ROM, median")
    axes.set_xscale("log")
    axes.set_xlabel(label)
by_step.set_ylabel("final slider position $x_C/L$")
by_step.legend(fontsize=8)
by_step.set_title("End state against the FE's time step")
by_wall.set_title("... and against its cost")
figure.tight_layout()
save_figure(figure, os.path.join(folder, "timestep_study.png"), dpi=120)
