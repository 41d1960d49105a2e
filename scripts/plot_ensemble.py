"""Fan chart of an ensemble (beamslider ensemble): every member's slider
position x_C/L (bottom) and amplitude envelope (top) against time, member 0
in black, the others in colour; the members' jumps marked.
Arguments: folder (with member_periods.csv and members.csv), title."""
import os
import sys

from plot_common import plt, save_figure, read_rows  # noqa: E402


def main(folder, title):
    series = {}
    for row in read_rows(os.path.join(folder, "member_periods.csv")):
        m = int(row["member"])
        s = series.setdefault(m, ([], [], []))
        s[0].append(float(row["t_s"]))
        s[1].append(float(row["x_over_L"]))
        s[2].append(float(row["amplitude_over_h"]))
    jumps = {}
    for row in read_rows(os.path.join(folder, "members.csv")):
        if row["jump_time_s"]:
            jumps[int(row["member"])] = float(row["jump_time_s"])
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    for m, (t, x, a) in sorted(series.items()):
        # Envelope: 0.1 s trailing mean of the per-period amplitude, and at
        # most ~2000 points per member (no screen shows more).
        n = max(1, round(0.1 / (t[1] - t[0]))) if len(t) > 1 else 1
        env, acc = [], 0.0
        for i, v in enumerate(a):
            acc += v - (a[i - n] if i >= n else 0.0)
            env.append(acc / min(i + 1, n))
        step = max(1, len(t) // 2000)
        style = dict(color="k", lw=1.2, zorder=3) if m == 0 else dict(lw=0.7, alpha=0.7)
        ax1.plot(t[::step], env[::step], label=f"member {m}" if m < 8 else None, **style)
        ax2.plot(t[::step], x[::step], **style)
        if m in jumps:
            ax1.axvline(jumps[m], color="tab:grey", lw=0.4, ls=":")
    ax1.set_ylabel("amplitude envelope / h")
    ax1.set_title(title)
    ax1.grid(alpha=0.3)
    ax1.legend(fontsize=7, ncol=4, loc="upper left")
    ax2.axhline(0.5, color="k", lw=0.5, ls=":")
    ax2.set_ylabel(r"slider $x_C/L$")
    ax2.set_xlabel("t [s]")
    ax2.grid(alpha=0.3)
    fig.tight_layout()
    save_figure(fig, os.path.join(folder, "ensemble.png"), dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
