"""Strong-scaling chart of beamslider map: cells computed per second against
the number of MPI ranks (markers and line), with the ideal linear scaling
from the 1-rank point as a dashed line (from the fewest-rank point if no
1-rank run is listed) and the parallel efficiency (measured / ideal) written
next to each point; the title names the machine of the first row. Axes are
logarithmic when the ranks span a factor of 8 or more.
Arguments: scaling.csv (columns ranks,cells,wall_s,cells_per_s,machine; an
empty cells_per_s is taken as cells / wall_s), output PNG."""
import csv
import math
import sys

from plot_common import plt, save_figure  # noqa: E402
from matplotlib.ticker import FuncFormatter

COLUMNS = ["ranks", "cells", "wall_s", "cells_per_s", "machine"]


def fail(message):
    sys.exit(f"plot_map_scaling.py: {message}")


def positive(text, what):
    try:
        v = float(text)
    except ValueError:
        v = math.nan
    if not (math.isfinite(v) and v > 0):
        fail(f"{what}: '{text}' is not a positive number")
    return v


def read(path):
    try:
        f = open(path, newline="")
    except OSError as e:
        fail(f"cannot read '{path}': {e.strerror}")
    with f:
        reader = csv.DictReader(f)
        missing = [c for c in COLUMNS if c not in (reader.fieldnames or [])]
        if missing:
            fail(f"{path} lacks the column(s) {', '.join(missing)}")
        points = []
        for line, row in enumerate(reader, start=2):
            where = f"{path} line {line}"
            if any(row.get(c) is None for c in COLUMNS):
                fail(f"{where}: expected {len(reader.fieldnames)} fields")
            ranks = positive(row["ranks"], f"{where}, ranks")
            if ranks != int(ranks):
                fail(f"{where}, ranks: '{row['ranks']}' is not a whole number")
            if row["cells_per_s"].strip():
                rate = positive(row["cells_per_s"], f"{where}, cells_per_s")
            else:
                rate = positive(row["cells"], f"{where}, cells") / positive(row["wall_s"], f"{where}, wall_s")
            points.append(dict(ranks=int(ranks), rate=rate, machine=row["machine"].strip()))
    if not points:
        fail(f"{path} holds no rows")
    return points


def main(src, out):
    points = read(src)
    machine = points[0]["machine"] or "unnamed machine"
    points.sort(key=lambda p: p["ranks"])
    ones = [p for p in points if p["ranks"] == 1]
    base = ones[0] if ones else points[0]
    per_rank = base["rate"] / base["ranks"]
    ranks = [p["ranks"] for p in points]
    rates = [p["rate"] for p in points]

    fig, ax = plt.subplots(figsize=(7, 5))
    span = [min(ranks), max(ranks)]
    ax.plot(span, [per_rank * r for r in span], "--", color="grey",
            label="ideal linear scaling" + ("" if ones else f" (from the {base['ranks']}-rank run)"))
    ax.plot(ranks, rates, "o-", color="tab:blue", label="measured")
    for r, rate in zip(ranks, rates):
        ax.annotate(f"{100 * rate / (per_rank * r):.0f} %", (r, rate), xytext=(6, -12), textcoords="offset points",
                    fontsize=8)
    if max(ranks) >= 8 * min(ranks):
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        plain = FuncFormatter(lambda v, _: f"{v:g}")
        ax.yaxis.set_major_formatter(plain)
        ax.yaxis.set_minor_formatter(plain)
        ax.set_xticks(sorted(set(ranks)))
        ax.set_xticklabels([str(r) for r in sorted(set(ranks))])
    else:
        ax.set_xticks(sorted(set(ranks)))
        ax.set_ylim(bottom=0)
    ax.set_xlabel("MPI ranks")
    ax.set_ylabel("cells per second")
    ax.set_title(f"beamslider map throughput on {machine}\n(numbers: parallel efficiency against ideal scaling)",
                 fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    save_figure(fig, out, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_map_scaling.py <scaling.csv> <output.png>")
    main(sys.argv[1], sys.argv[2])
