"""Chart of report section 5.5: the explicit ROM scheme's stable time step
2/omega_N against the number of modes N, the seed's rule 2 pi/(5 omega_N) and
the scene's time step. Arguments: report folder (with
explicit_time_step_limit.csv), the scene's time step [s]."""
import sys

from plot_common import plt, save_figure, read_rows  # noqa: E402


def main(folder, dt):
    rows = read_rows(f"{folder}/explicit_time_step_limit.csv")
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
    save_figure(fig, f"{folder}/explicit_time_step_limit.png", dpi=120)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
