"""Charts for the verification section "Linear frequencies".

Reads frequency_convergence.csv and bonded_slider.csv from the report folder
given as the only argument and writes frequency_convergence.png and
bonded_slider.png beside them.
"""
import sys

from plot_common import plt, save_figure, read_rows  # noqa: E402


def main(folder):
    rows = read_rows(f"{folder}/frequency_convergence.csv")
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for ax, supports in zip(axes, ["clamped", "elastic"]):
        modes = sorted({int(r["mode"]) for r in rows})
        for mode in modes:
            sel = [r for r in rows if r["supports"] == supports and int(r["mode"]) == mode]
            n = [int(r["n_elements"]) for r in sel]
            err = [max(float(r["relative_error"]), 1e-16) for r in sel]
            ax.loglog(n, err, "o-", label=f"mode {mode}")
        n_ref = [8, 64]
        ax.loglog(n_ref, [1e-2 * (n_ref[0] / x) ** 4 for x in n_ref], "k--", label="slope −4")
        ax.set_xlabel("number of elements")
        ax.set_title({"clamped": "ideal clamp vs cos βL cosh βL = 1",
                      "elastic": "rotational springs vs characteristic eq."}[supports])
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("relative frequency error")
    axes[1].legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, f"{folder}/frequency_convergence.png", dpi=120)

    rows = read_rows(f"{folder}/bonded_slider.csv")
    x = [float(r["x_over_L"]) for r in rows]
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    ax.plot(x, [float(r["fe_fine_frequency_hz"]) for r in rows], "k-", label="FE, slider bonded (128 el.)")
    ax.plot(x, [float(r["fe_frequency_hz"]) for r in rows], "bo", ms=3, label="FE, default mesh")
    ax.plot(x, [float(r["eq5_frequency_hz"]) for r in rows], "g--", label="seed Eq. 5 (Rayleigh quotient)")
    ax.set_ylabel("first natural frequency [Hz]")
    ax.legend()
    ax.grid(alpha=0.3)
    ax2.plot(x, [100 * float(r["eq5_relative_difference"]) for r in rows], "g-")
    ax2.set_xlabel("slider position x_C/L")
    ax2.set_ylabel("(Eq. 5 − FE)/FE [%]")
    ax2.grid(alpha=0.3)
    fig.tight_layout()
    save_figure(fig, f"{folder}/bonded_slider.png", dpi=120)


if __name__ == "__main__":
    main(sys.argv[1])
