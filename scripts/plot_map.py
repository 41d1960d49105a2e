"""Heat maps of an operating map (beamslider map): for every grid cell the
outcome class the most members reached (ties: the first class in CLASSES),
the median final slider position x_C/L and the median late amplitude w/h.

For every pair of grid axes <a>, <b> it writes map_outcome_<a>_<b>.png (one
fixed colour per class; "k/K" = members agreeing with the majority, when a
cell has K > 1 members), map_final_position_<a>_<b>.png and
map_late_amplitude_<a>_<b>.png; with more than two axes the other axes are
held at their first (smallest) grid value. With a single axis it writes
map_line_<a>.png (class, final position, late amplitude against the axis).
Cells missing from map.csv stay blank. The published cases of
published_cases.csv (if present) that lie in the plotted plane are marked
with a star and their name: black, or red where the expected outcome differs
from the majority class of the cell they lie in.

Arguments: map folder (with map.csv), title text. Prints nothing on standard
output (beamslider's --quiet holds for its charts too); problems go to
standard error."""
import csv
import itertools
import math
import os
import statistics
import sys

import matplotlib.colors as mcolors
import matplotlib.patches as mpatches
from plot_common import plt, save_figure  # noqa: E402
import numpy as np

# The outcome classes in tie-breaking order, each with its fixed colour.
CLASSES = [
    ("signature move", "#1f77b4"),
    ("trivial adaption", "#2ca02c"),
    ("relaxation oscillation", "#ff7f0e"),
    ("self-damping", "#9467bd"),
    ("no adaptation", "#bcbd22"),
    ("reached a support", "#8c564b"),
    ("failed", "#4d4d4d"),
    ("too short to judge", "#c7c7c7"),
]
CLASS_NAMES = [c for c, _ in CLASSES]
CLASS_INDEX = {c: i for i, c in enumerate(CLASS_NAMES)}
CLASS_CMAP = mcolors.ListedColormap([col for _, col in CLASSES])
CLASS_NORM = mcolors.BoundaryNorm(np.arange(-0.5, len(CLASSES) + 0.5), len(CLASSES))

AFTER_AXES = ["member", "perturbation", "status", "outcome", "final_x_over_L", "late_amplitude_over_h",
              "adaptation_time_s", "jump_count", "first_jump_time_s"]
LABELS = {
    "frequency_hz": "excitation frequency [Hz]",
    "acceleration_m_s2": "base acceleration amplitude [m/s²]",
    "start_x_over_L": "start position x_C/L",
}
REL_TOL = 1e-9


def fail(message):
    sys.exit(f"plot_map.py: {message}")


def label(axis):
    return LABELS.get(axis, axis)


def same(a, b):
    return abs(a - b) <= REL_TOL * max(abs(a), abs(b))


def number(text, what):
    try:
        v = float(text)
    except ValueError:
        v = math.nan
    if not math.isfinite(v):
        fail(f"{what}: '{text}' is not a number")
    return v


def optional_number(text, what):
    return math.nan if text.strip() == "" else number(text, what)


def read_map(path):
    """Returns (axes, cells): cells maps the tuple of grid values to the list
    of member rows {outcome, final, late}."""
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        header = reader.fieldnames or []
        if "member" not in header:
            fail(f"{path} has no 'member' column (header: {','.join(header) or 'empty'})")
        axes = header[:header.index("member")]
        if not axes:
            fail(f"{path} has no axis column before 'member'")
        missing = [c for c in AFTER_AXES if c not in header]
        if missing:
            fail(f"{path} lacks the column(s) {', '.join(missing)}")
        members = {}
        for line, row in enumerate(reader, start=2):
            where = f"{path} line {line}"
            if None in row or any(row[c] is None for c in header):
                fail(f"{where}: expected {len(header)} fields")
            key = tuple(number(row[a], f"{where}, {a}") for a in axes)
            outcome = row["outcome"].strip()
            if outcome not in CLASS_INDEX:
                fail(f"{where}: unknown outcome '{outcome}' (known: {', '.join(CLASS_NAMES)})")
            member = row["member"].strip()
            if (key, member) in members:
                print(f"plot_map.py: {where}: member {member} of this cell appears again; the last row counts",
                      file=sys.stderr)
            members[(key, member)] = dict(outcome=outcome,
                                          final=optional_number(row["final_x_over_L"], f"{where}, final_x_over_L"),
                                          late=optional_number(row["late_amplitude_over_h"],
                                                               f"{where}, late_amplitude_over_h"))
    if not members:
        fail(f"{path} holds no rows")
    cells = {}
    for (key, _), m in members.items():
        cells.setdefault(key, []).append(m)
    return axes, cells


def grid_values(cells, n_axes):
    """The sorted distinct values of every axis (equal within REL_TOL merged)."""
    grids = []
    for i in range(n_axes):
        values = []
        for v in sorted(k[i] for k in cells):
            if not values or not same(values[-1], v):
                values.append(v)
        grids.append(fill_gaps(values))
    return grids


def fill_gaps(values):
    """A grid value whose cells are all missing (a row or column not yet
    computed) leaves no trace in map.csv: where the values are whole multiples
    of the smallest step apart, the missing ones are put back (blank)."""
    if len(values) < 3:
        return values
    step = min(b - a for a, b in zip(values, values[1:]))
    multiples = [(b - a) / step for a, b in zip(values, values[1:])]
    if any(abs(m - round(m)) > 1e-6 * m for m in multiples) or sum(round(m) for m in multiples) > 10000:
        return values
    filled = [values[0]]
    for a, b, m in zip(values, values[1:], multiples):
        n = round(m)
        filled += [a + k * (b - a) / n for k in range(1, n)]
        filled.append(b)
    return filled


def snap(value, grid):
    """Index of the grid value equal to value (within REL_TOL), or None."""
    for i, g in enumerate(grid):
        if same(g, value):
            return i
    return None


def nearest(value, grid):
    """Index of the nearest grid value if value lies within half a step of
    it (on a one-value axis: equal to it), else None."""
    i = min(range(len(grid)), key=lambda j: abs(grid[j] - value))
    if same(grid[i], value):
        return i
    if len(grid) == 1:
        return None
    neighbour = grid[i + 1] if value > grid[i] and i + 1 < len(grid) else grid[i - 1] if i > 0 else grid[i + 1]
    return i if abs(value - grid[i]) <= 0.5 * abs(neighbour - grid[i]) * (1 + REL_TOL) else None


def summarize(members):
    counts = {}
    for m in members:
        counts[m["outcome"]] = counts.get(m["outcome"], 0) + 1
    majority = max(counts, key=lambda c: (counts[c], -CLASS_INDEX[c]))
    finals = [m["final"] for m in members if not math.isnan(m["final"])]
    lates = [m["late"] for m in members if not math.isnan(m["late"])]
    return dict(outcome=majority, agree=counts[majority], members=len(members),
                final=statistics.median(finals) if finals else math.nan,
                late=statistics.median(lates) if lates else math.nan)


def edges(grid):
    """Cell edges for pcolormesh: midway between grid values, half a step
    beyond the ends."""
    g = np.asarray(grid, dtype=float)
    if len(g) == 1:
        d = 0.05 * abs(g[0]) if g[0] != 0 else 0.5
        return np.array([g[0] - d, g[0] + d])
    mid = 0.5 * (g[1:] + g[:-1])
    return np.concatenate([[g[0] - (mid[0] - g[0])], mid, [g[-1] + (g[-1] - mid[-1])]])


def read_cases(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        header = reader.fieldnames or []
        if "name" not in header:
            fail(f"{path} has no 'name' column")
        cases = []
        for line, row in enumerate(reader, start=2):
            coordinates = {}
            for c in header:
                if c in ("name", "expected_outcome") or c is None or row.get(c) is None or not row[c].strip():
                    continue
                coordinates[c] = number(row[c], f"{path} line {line}, {c}")
            cases.append(dict(name=row["name"], expected=(row.get("expected_outcome") or "").strip(),
                              at=coordinates))
    return cases


def cases_in_plane(cases, axes, grids, free, fixed):
    """The cases whose coordinates on the axes in `fixed` (index -> grid
    value) match (missing = any) and that have a value on every free axis.
    Yields (case, free values, index tuple of the nearest cell or None)."""
    for case in cases:
        if any(axes[i] in case["at"] and not same(case["at"][axes[i]], v) for i, v in fixed.items()):
            continue
        if not all(axes[i] in case["at"] for i in free):
            continue
        values = [case["at"][axes[i]] for i in free]
        index = [None] * len(axes)
        for i, v in fixed.items():
            index[i] = snap(v, grids[i])
        for i, v in zip(free, values):
            index[i] = nearest(v, grids[i])
        yield case, values, (tuple(index) if None not in index else None)


def star_colour(case, cell):
    if cell is None or not case["expected"]:
        return "k"
    return "tab:red" if case["expected"] != cell["outcome"] else "k"


def text_colour(hex_colour):
    r, g, b = mcolors.to_rgb(hex_colour)
    return "k" if 0.299 * r + 0.587 * g + 0.114 * b > 0.5 else "w"


def within(value, e):
    return e[0] <= value <= e[-1]


def plot_pair(folder, title, axes, grids, summary, cases, ia, ib):
    a, b = axes[ia], axes[ib]
    fixed = {i: grids[i][0] for i in range(len(axes)) if i not in (ia, ib)}
    ga, gb = grids[ia], grids[ib]
    outcome = np.full((len(gb), len(ga)), np.nan)
    final = np.full_like(outcome, np.nan)
    late = np.full_like(outcome, np.nan)
    agree = {}
    for key, s in summary.items():
        if any(not same(key[i], v) for i, v in fixed.items()):
            continue
        x, y = snap(key[ia], ga), snap(key[ib], gb)
        outcome[y, x] = CLASS_INDEX[s["outcome"]]
        final[y, x] = s["final"]
        late[y, x] = s["late"]
        if s["members"] > 1:
            agree[(x, y)] = f"{s['agree']}/{s['members']}"
    if np.all(np.isnan(outcome)):
        print(f"plot_map.py: no cell of map.csv lies in the plane {a}, {b} at the first values of the other axes",
              file=sys.stderr)
    ea, eb = edges(ga), edges(gb)
    heading = title
    if fixed:
        heading += "\n" + ", ".join(f"{label(axes[i])} = {v:g}" for i, v in fixed.items()) + \
                   " (held at the first grid value)"
    marks = []
    for case, (va, vb), index in cases_in_plane(cases, axes, grids, (ia, ib), fixed):
        if not (within(va, ea) and within(vb, eb)):
            print(f"plot_map.py: published case {case['name']} ({a} = {va:g}, {b} = {vb:g}) lies outside the map",
                  file=sys.stderr)
            continue
        cell = summary.get(tuple(grids[i][j] for i, j in enumerate(index))) if index else None
        marks.append((case["name"], va, vb, star_colour(case, cell)))

    written = []

    def finish(fig, ax, name):
        for text, va, vb, colour in marks:
            ax.plot(va, vb, "*", ms=14, color=colour, mec="w", mew=0.8, zorder=5)
            ax.annotate(text, (va, vb), xytext=(6, 5), textcoords="offset points", fontsize=7, color=colour,
                        zorder=6, bbox=dict(boxstyle="round,pad=0.15", fc="w", ec="none", alpha=0.7))
        ax.set_xlim(ea[0], ea[-1])
        ax.set_ylim(eb[0], eb[-1])
        ax.set_xlabel(label(a))
        ax.set_ylabel(label(b))
        fig.tight_layout()
        path = os.path.join(folder, f"{name}_{a}_{b}.png")
        save_figure(fig, path, dpi=120)
        plt.close(fig)
        written.append(path)

    fig, ax = plt.subplots(figsize=(8.5, 5.5))
    ax.pcolormesh(ea, eb, np.ma.masked_invalid(outcome), cmap=CLASS_CMAP, norm=CLASS_NORM,
                  edgecolors="w", linewidth=0.3)
    small = max(4.0, min(7.0, 90.0 / max(len(ga), len(gb))))
    for (x, y), text in agree.items():
        colour = text_colour(CLASSES[int(outcome[y, x])][1])
        ax.text(ga[x], gb[y], text, ha="center", va="center", fontsize=small, color=colour)
    present = sorted({int(v) for v in outcome[~np.isnan(outcome)]})
    if present:
        ax.legend(handles=[mpatches.Patch(color=CLASSES[i][1], label=CLASSES[i][0]) for i in present],
                  fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    ax.set_title(heading + "\noutcome class of the majority of members" +
                 (" (k/K: members agreeing)" if agree else ""), fontsize=9)
    finish(fig, ax, "map_outcome")

    for values, name, what, cmap in ((final, "map_final_position", "$x_C/L$", "viridis"),
                                     (late, "map_late_amplitude", r"$\hat w/h$", "magma")):
        fig, ax = plt.subplots(figsize=(7.5, 5.5))
        data = values[~np.isnan(values)]
        if name == "map_final_position":
            low, high = (max(0.0, data.min()), min(1.0, data.max())) if data.size else (0.0, 1.0)
        else:
            low, high = (data.min(), data.max()) if data.size else (0.0, 1.0)
        if high <= low:
            low, high = low - 0.05, high + 0.05
        mesh = ax.pcolormesh(ea, eb, np.ma.masked_invalid(values), cmap=cmap, vmin=low, vmax=high,
                             edgecolors="w", linewidth=0.3)
        fig.colorbar(mesh, ax=ax, label=what)
        ax.set_title(heading + f"\nmedian over members of the {'final slider position' if name == 'map_final_position' else 'late amplitude'}",
                     fontsize=9)
        finish(fig, ax, name)
    return written


def plot_line(folder, title, axes, grids, summary, cases):
    a = axes[0]
    g = grids[0]
    cells = [summary.get((v,)) for v in g]
    e = edges(g)
    marks = []
    for case, (v,), index in cases_in_plane(cases, axes, grids, (0,), {}):
        if not within(v, e):
            print(f"plot_map.py: published case {case['name']} ({a} = {v:g}) lies outside the map", file=sys.stderr)
            continue
        cell = cells[index[0]] if index else None
        expected = case["expected"] if case["expected"] in CLASS_INDEX else cell["outcome"] if cell else None
        if expected is not None:
            marks.append((case["name"], v, expected, star_colour(case, cell)))
    # One row per class shown, in the order of CLASSES.
    rows = sorted({CLASS_INDEX[c["outcome"]] for c in cells if c} | {CLASS_INDEX[m[2]] for m in marks})
    row_of = {CLASS_NAMES[i]: r for r, i in enumerate(rows)}

    fig, (ax1, ax2, ax3) = plt.subplots(3, 1, figsize=(8, 8), sharex=True,
                                        gridspec_kw=dict(height_ratios=[1.2, 1, 1]))
    for v, c in zip(g, cells):
        if c is None:
            continue
        ax1.plot(v, row_of[c["outcome"]], "s", color=CLASSES[CLASS_INDEX[c["outcome"]]][1], ms=9, mec="k", mew=0.4)
        if c["members"] > 1:
            ax1.annotate(f"{c['agree']}/{c['members']}", (v, row_of[c["outcome"]]), xytext=(0, 7),
                         textcoords="offset points", ha="center", fontsize=6)
    # NaN (missing cell or no value) breaks the line.
    ax2.plot(g, [c["final"] if c else math.nan for c in cells], "o-", color="tab:blue", ms=4)
    ax2.set_ylabel("median final $x_C/L$")
    ax3.plot(g, [c["late"] if c else math.nan for c in cells], "o-", color="tab:purple", ms=4)
    ax3.set_ylabel(r"median late $\hat w/h$")
    for name, v, expected, colour in marks:
        ax1.plot(v, row_of[expected], "*", ms=15, color=colour, mec="w", mew=0.8, zorder=5)
        ax1.annotate(name, (v, row_of[expected]), xytext=(7, -10), textcoords="offset points", fontsize=7,
                     color=colour)
        for ax in (ax2, ax3):
            ax.axvline(v, color=colour, lw=0.6, ls=":")
    ax1.set_yticks(range(len(rows)))
    ax1.set_yticklabels([CLASS_NAMES[i] for i in rows], fontsize=8)
    ax1.set_ylim(len(rows) - 0.4, -0.6)
    ax1.set_title(title + "\nmajority outcome class (k/K: members agreeing; star: published case, red if it "
                  "disagrees)", fontsize=9)
    for ax in (ax1, ax2, ax3):
        ax.grid(alpha=0.3)
    ax3.set_xlabel(label(a))
    ax3.set_xlim(e[0], e[-1])
    fig.tight_layout()
    path = os.path.join(folder, f"map_line_{a}.png")
    save_figure(fig, path, dpi=120)
    plt.close(fig)
    return [path]


def main(folder, title):
    path = os.path.join(folder, "map.csv")
    if not os.path.isfile(path):
        fail(f"no map.csv in '{folder}'")
    axes, cells = read_map(path)
    grids = grid_values(cells, len(axes))
    # Key every cell by the canonical grid values.
    summary = {}
    for key, members in cells.items():
        canonical = tuple(grids[i][snap(v, grids[i])] for i, v in enumerate(key))
        summary.setdefault(canonical, []).extend(members)
    summary = {k: summarize(m) for k, m in summary.items()}
    cases = read_cases(os.path.join(folder, "published_cases.csv"))
    if len(axes) == 1:
        plot_line(folder, title, axes, grids, summary, cases)
    else:
        for ia, ib in itertools.combinations(range(len(axes)), 2):
            plot_pair(folder, title, axes, grids, summary, cases, ia, ib)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_map.py <map folder> <title text>")
    main(sys.argv[1], sys.argv[2])
