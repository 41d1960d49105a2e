"""Chart of the held slider's slow manifold (seed Fig. 10b): branches.png in
the given folder, from branches.csv, attractor.csv and branch_events.csv.
Top: amplitude of w(L/2) over h against x_C/L, the attached-slider model's
periodic orbits (stable solid, unstable dashed), its turning points, and the
rattling held slider's probes (mean amplitude over the section). Bottom: the
probes' largest Lyapunov exponent per excitation period (> 0: chaos, no
periodic orbit)."""
import os
import sys

from plot_common import plt, save_figure, read_rows  # noqa: E402


def segments(rows):
    """Runs of consecutive rows with the same stability."""
    run = []
    for r in rows:
        if run and r["stable"] != run[-1]["stable"]:
            yield run
            run = [run[-1]]
        run.append(r)
    if run:
        yield run


def main(folder, scene):
    orbits = read_rows(os.path.join(folder, "branches.csv"), missing_ok=True)
    probes = read_rows(os.path.join(folder, "attractor.csv"), missing_ok=True)
    events = read_rows(os.path.join(folder, "branch_events.csv"), missing_ok=True)
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    labelled = set()
    for run in segments(orbits):
        stable = run[-1]["stable"] == "1"
        label = "attached model, " + ("stable" if stable else "unstable")
        ax1.plot([float(r["x_over_L"]) for r in run], [float(r["amplitude_over_h"]) for r in run],
                 "-" if stable else "--", color="tab:blue",
                 label=None if label in labelled else label)
        labelled.add(label)
    for e in events:
        ax1.plot(float(e["x_over_L"]), float(e["amplitude_over_h"]), "s", color="tab:red", ms=5,
                 label=None if "event" in labelled else "turning point / bifurcation")
        labelled.add("event")
    if probes:
        x = [float(r["x_over_L"]) for r in probes]
        ax1.plot(x, [float(r["amplitude_over_h"]) for r in probes], "o", ms=4, color="tab:orange",
                 label="rattling held slider (probes)")
        ax2.plot(x, [float(r["lyapunov_per_period"]) for r in probes], "o-", ms=4, color="tab:orange")
    ax2.axhline(0, color="k", lw=0.6)
    ax1.set_ylabel(r"amplitude $\hat w_{L/2}/h$")
    ax1.set_title(f"Slow manifold of the held slider: scene {scene}")
    ax1.legend(fontsize=8)
    ax1.grid(alpha=0.3)
    ax2.set_xlabel(r"slider position $x_C/L$")
    ax2.set_ylabel("largest Lyapunov exponent [1/period]")
    ax2.grid(alpha=0.3)
    fig.tight_layout()
    save_figure(fig, os.path.join(folder, "branches.png"), dpi=120)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "")
