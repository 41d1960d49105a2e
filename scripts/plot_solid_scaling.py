"""Strong scaling of the solid's modes + STEP (scripts/solid_scaling.sh):
left, the speed-up over 1 rank against the number of ranks, one line per
mesh size, with ideal scaling dashed; right, wall time and the busiest
rank's memory against DoFs, one line per rank count, on logarithmic axes.
Arguments: solid_scaling.csv (columns dofs,ranks,wall_s,modes_s,max_rss_mb,
machine), output PNG."""
import sys

from plot_common import plt, save_figure, positive_number, read_checked_rows  # noqa: E402
from matplotlib.ticker import FuncFormatter

COLUMNS = ["dofs", "ranks", "wall_s", "modes_s", "max_rss_mb", "machine"]
SCRIPT = "plot_solid_scaling.py"


def read(path):
    rows = []
    for line, row in read_checked_rows(path, COLUMNS, SCRIPT):
        where = f"{path} line {line}"

        def number(column):
            return positive_number(row[column], f"{where}, {column}", SCRIPT)

        rows.append(dict(dofs=int(number("dofs")), ranks=int(number("ranks")), wall=number("wall_s"),
                         rss=number("max_rss_mb"), machine=(row["machine"] or "").strip()))
    return rows


def main(src, out):
    rows = read(src)
    machine = rows[0]["machine"] or "unnamed machine"
    sizes = sorted({r["dofs"] for r in rows})
    rank_counts = sorted({r["ranks"] for r in rows})
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))

    left.plot([1, max(rank_counts)], [1, max(rank_counts)], "--", color="grey", label="ideal")
    for n in sizes:
        runs = sorted((r for r in rows if r["dofs"] == n), key=lambda r: r["ranks"])
        one = [r for r in runs if r["ranks"] == 1]
        if not one:
            continue
        left.plot([r["ranks"] for r in runs], [one[0]["wall"] / r["wall"] for r in runs], "o-",
                  label=f"{n:,} DoFs".replace(",", " "))
    left.set_xticks(rank_counts)
    left.set_xlabel("MPI ranks")
    left.set_ylabel("speed-up over 1 rank")
    left.set_ylim(bottom=0)
    left.grid(True, alpha=0.3)
    left.legend(fontsize=8, loc="upper left")

    memory = right.twinx()
    for p in rank_counts:
        runs = sorted((r for r in rows if r["ranks"] == p), key=lambda r: r["dofs"])
        x = [r["dofs"] for r in runs]
        right.plot(x, [r["wall"] for r in runs], "o-", label=f"wall time, {p} rank(s)")
        memory.plot(x, [r["rss"] / 1024 for r in runs], "s:", label=f"memory of the busiest rank, {p} rank(s)")
    plain = FuncFormatter(lambda v, _: f"{v:g}")
    for ax in (right, memory):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.yaxis.set_major_formatter(plain)
        ax.yaxis.set_minor_formatter(plain)
    right.set_xlabel("DoFs")
    right.set_ylabel("wall time [s] (circles)")
    memory.set_ylabel("memory per rank [GB] (squares)")
    right.grid(True, which="both", alpha=0.3)
    lines = right.get_legend_handles_labels()
    more = memory.get_legend_handles_labels()
    right.legend(lines[0] + more[0], lines[1] + more[1], fontsize=7, loc="upper left")
    fig.suptitle(f"beamslider: solid strip, modes + STEP (N = 5), on {machine}", fontsize=9)
    fig.tight_layout()
    save_figure(fig, out, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_solid_scaling.py <solid_scaling.csv> <output.png>")
    main(sys.argv[1], sys.argv[2])
