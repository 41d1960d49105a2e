#!/usr/bin/env python3
"""A strip of still frames of a beam-slider animation (beamslider animate).

Reads frames.csv (columns frame, t_s, part, x_m, z_m, fx_N, fz_N: the drawn
geometry, magnification as written in the file's first line) and draws up to
six frames evenly spaced in time, stacked, into one PNG. The z axis is
stretched (aspect not equal) so that the 1 mm beam stays visible next to its
140 mm length; contact forces are arrows scaled to the largest force shown.

usage: plot_frames.py frames.csv frames.png [n_frames]
"""
import csv
import re
import sys
from collections import defaultdict

from plot_common import plt, save_figure  # noqa: E402


def read(path):
    frames = defaultdict(lambda: defaultdict(list))
    times = {}
    header, lines = "", []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                header = header or line
            else:
                lines.append(line)
    for row in csv.DictReader(lines):
        k = int(row["frame"])
        times[k] = float(row["t_s"])
        frames[k][row["part"]].append(
            (float(row["x_m"]), float(row["z_m"]), float(row["fx_N"]), float(row["fz_N"]))
        )
    return frames, times, header.strip("# \n")


def main():
    src, dst = sys.argv[1], sys.argv[2]
    n_show = int(sys.argv[3]) if len(sys.argv) > 3 else 6
    frames, times, note = read(src)
    keys = sorted(frames)
    if not keys:
        sys.exit("no frames in " + src)
    n_show = min(n_show, len(keys))
    chosen = [keys[round(i * (len(keys) - 1) / max(n_show - 1, 1))] for i in range(n_show)]
    f_max = max(
        (abs(complex(p[2], p[3])) for k in chosen for p in frames[k]["contact"]), default=0.0
    ) or 1.0
    fig, axes = plt.subplots(n_show, 1, figsize=(9, 1.6 * n_show), sharex=True, squeeze=False)
    for ax, k in zip(axes[:, 0], chosen):
        parts = frames[k]
        top, bottom = parts["beam_top"], parts["beam_bottom"]
        xs = [p[0] * 1e3 for p in top] + [p[0] * 1e3 for p in reversed(bottom)]
        zs = [p[1] * 1e3 for p in top] + [p[1] * 1e3 for p in reversed(bottom)]
        ax.fill(xs, zs, color="0.6", lw=0.5, ec="k", label="beam")
        for part, style in (("slider_outer", "C0-"), ("slider_window", "C0--")):
            pts = parts[part]
            ax.plot([p[0] * 1e3 for p in pts], [p[1] * 1e3 for p in pts], style, lw=1)
        for x, z, fx, fz in parts["contact"]:
            if fx or fz:
                s = 4.0 / f_max  # 4 mm for the largest force
                ax.annotate("", xy=(x * 1e3 + s * fx, z * 1e3 + s * fz), xytext=(x * 1e3, z * 1e3),
                            arrowprops=dict(arrowstyle="->", color="C3", lw=1.2))
        ax.set_ylabel("z [mm]")
        ax.set_title(f"t = {times[k] * 1e3:.2f} ms", fontsize=9, loc="left")
    axes[-1, 0].set_xlabel("x [mm]")
    m = re.search(r"magnification ([0-9.eE+-]+)", note)
    fig.suptitle(f"beam and slider, transverse displacement x{m.group(1) if m else '?'} "
                 f"(z axis stretched); red: contact force on the slider, longest arrow {f_max:.3g} N",
                 fontsize=9)
    fig.tight_layout()
    save_figure(fig, dst, dpi=130)


if __name__ == "__main__":
    main()
