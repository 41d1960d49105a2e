"""Chart for the verification section "Cubic coefficients": relative error of
b_111 against the STEP amplitude / ICE load level (coefficient_load_levels.csv
in the report folder given as the only argument) -> coefficient_load_levels.png."""
import sys

from plot_common import plt, save_figure, read_rows  # noqa: E402


def main(folder):
    rows = read_rows(f"{folder}/coefficient_load_levels.csv")
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for (method, n), style in {("step-condensed", "1"): "ks-", ("ice", "1"): "bo-", ("ice", "3"): "r^-"}.items():
        sel = [r for r in rows if r["method"] == method and r["n_modes"] == n and r["status"] == "ok"]
        x = [float(r["level_over_h"]) for r in sel]
        y = [max(abs(float(r["b111_relative_error"])), 1e-16) for r in sel]
        ax.loglog(x, y, style, label=f"{method}, N = {n}")
        failed = [float(r["level_over_h"]) for r in rows
                  if r["method"] == method and r["n_modes"] == n and r["status"] == "failed"]
        if failed:
            ax.plot(failed, [1e-1] * len(failed), "x", color=style[0], ms=10, label=f"{method} N={n}: Newton failed")
    ax.axhline(1e-3, color="gray", ls=":", label="1e-3")
    ax.set_xlabel("STEP amplitude / ICE load level (linear displacement) [h]")
    ax.set_ylabel("|b_111 / analytic − 1|")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, f"{folder}/coefficient_load_levels.png", dpi=120)


if __name__ == "__main__":
    main(sys.argv[1])
