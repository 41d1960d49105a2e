"""Backbone charts.

  plot_backbones.py command DIR   DIR/backbone.csv + DIR/eq4.csv -> DIR/backbone.png
  plot_backbones.py report DIR    the report's section 3 (files backbone_*.csv in DIR):
                                  backbones.png (ROM N = 1, 3, 5, 7, FE, Eq. 4: seed Fig. 3)
                                  backbone_harmonics.png (H study on ROM N = 5)

Amplitude: first-harmonic amplitude of w(L/2) relative to the base, over h.
Each continuation segment is drawn as its own line: the gap between segments
is the internal-resonance tongue jumped over."""
import sys

from plot_common import plt, save_figure, read_rows  # noqa: E402


def segments(rows):
    """Split rows (amplitude_over_h, frequency_hz, segment) into lists per segment."""
    out = {}
    for r in rows:
        out.setdefault(int(r.get("segment", 0)), []).append((float(r["frequency_hz"]), float(r["amplitude_over_h"])))
    return [out[k] for k in sorted(out)]


def draw(ax, rows, style, label, **kw):
    """The backbone segments in `style`; the tongue excursions thin and grey."""
    for i, seg in enumerate(segments([r for r in rows if r.get("branch", "backbone") == "backbone"])):
        ax.plot([p[0] for p in seg], [p[1] for p in seg], style, label=label if i == 0 else None, **kw)
    for seg in segments([r for r in rows if r.get("branch", "backbone") == "tongue"]):
        ax.plot([p[0] for p in seg], [p[1] for p in seg], "-", color="0.6", lw=0.7)


def command(folder):
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    draw(ax, read_rows(f"{folder}/backbone.csv"), "b.-", "harmonic balance", ms=3)
    draw(ax, read_rows(f"{folder}/eq4.csv"), "k--", "seed Eq. 4 (one mode, one harmonic)")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("ŵ(L/2) / h (first harmonic)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, f"{folder}/backbone.png", dpi=120)


def report(folder):
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    styles = {"rom_N1": ("c-", "ROM N = 1"), "rom_N3": ("g-", "ROM N = 3"), "rom_N5": ("b-", "ROM N = 5"),
              "rom_N7": ("m-", "ROM N = 7"), "rom_N15": ("y-", "ROM N = 15"), "fe": ("r:", "FE (full model)"), "eq4": ("k--", "seed Eq. 4")}
    for ax, name, title in ((axes[0], "backbone_curves.csv", "scene as given"),
                            (axes[1], "backbone_ideal_curves.csv", "ideal clamp")):
        try:
            rows = read_rows(f"{folder}/{name}")
        except FileNotFoundError:
            ax.set_visible(False)
            continue
        for key, (style, label) in styles.items():
            sel = [r for r in rows if r["curve"] == key]
            if sel:
                draw(ax, sel, style, label, lw=2 if key == "fe" else 1.2)
        ax.set_xlabel("frequency [Hz]")
        ax.set_ylabel("ŵ(L/2) / h (first harmonic)")
        ax.set_title(f"Mode-1 backbones, H = 10, {title}\n(grey: tongue followed before the jump)", fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, f"{folder}/backbones.png", dpi=120)

    rows = read_rows(f"{folder}/backbone_harmonics.csv")
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for H, style in {"1": "ks-", "3": "bo-", "5": "r^-"}.items():
        sel = [r for r in rows if r["n_harmonics"] == H and r["difference_hz"] != ""]
        x = [float(r["amplitude_over_h"]) for r in sel]
        y = [max(abs(float(r["relative_difference"])), 1e-16) for r in sel]
        ax.semilogy(x, y, style, label=f"H = {H}")
    ax.set_xlabel("ŵ(L/2) / h")
    ax.set_ylabel("|f_H / f_(H=10) − 1|  (ROM N = 5)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, f"{folder}/backbone_harmonics.png", dpi=120)


if __name__ == "__main__":
    {"command": command, "report": report}[sys.argv[1]](sys.argv[2])
