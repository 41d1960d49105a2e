#!/usr/bin/env bash
# Strong scaling of the solid: `coefficients mueller2023-ideal-solid --method
# step` (the modes by SLEPc/MUMPS, then plain STEP on N = 5) on generated 3D
# strips of growing size, each on 1, 2, … ranks; written as solid_scaling.csv
# (dofs,ranks,wall_s,modes_s,max_rss_mb,machine) and drawn by
# plot_solid_scaling.py as solid_scaling.png in the output folder.
#     bash scripts/solid_scaling.sh [OUTPUT_DIR] [MAX_RANKS]
# Run from the repository root after building. As root (a container), Open
# MPI needs OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1.
# max_rss_mb is GNU time's largest resident set of one process of the run:
# the memory of the busiest rank.
set -euo pipefail
out="${1:-reports/mueller2023-ideal-solid/scaling}"
max_ranks="${2:-$(nproc)}"
program="build/beamslider"
[[ -x "$program" ]] || { echo "solid_scaling.sh: $program not found; build first" >&2; exit 1; }
[[ -x /usr/bin/time ]] || { echo "solid_scaling.sh: GNU time (/usr/bin/time, Debian package 'time') is needed" >&2; exit 1; }
mkdir -p "$out"
machine="$(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
echo "dofs,ranks,wall_s,modes_s,max_rss_mb,machine" > "$out/solid_scaling.csv"
# Elements along the length, across the width, through the thickness:
# 11 421, 39 195 and 126 315 DoFs with Q2.
for mesh in "70 4 1" "100 6 2" "200 10 2"; do
  read -r nx ny nz <<< "$mesh"
  args=(coefficients mueller2023-ideal-solid --method step
        --set "Solid/Elements along length=$nx" --set "Solid/Elements across width=$ny"
        --set "Solid/Elements through thickness=$nz")
  for ((p = 1; p <= max_ranks; p *= 2)); do
    dir="$out/${nx}x${ny}x${nz}_ranks_$p"
    rm -rf "$dir"
    launcher=()
    ((p > 1)) && launcher=(mpirun -np "$p")
    /usr/bin/time -f "%M" -o "$out/rss.txt" "${launcher[@]}" "$program" "${args[@]}" --output "$dir" > /dev/null
    # summary.md: "- solid: 3d, ..., N DoFs, ..." and "- wall time: W s (modes M s)"
    dofs="$(grep -m1 '^- solid:' "$dir/summary.md" | sed -E 's/.* ([0-9]+) DoFs.*/\1/')"
    wall="$(grep -m1 '^- wall time:' "$dir/summary.md" | sed -E 's/- wall time: ([0-9.e+-]+) s \(modes ([0-9.e+-]+) s\)/\1/')"
    modes="$(grep -m1 '^- wall time:' "$dir/summary.md" | sed -E 's/- wall time: ([0-9.e+-]+) s \(modes ([0-9.e+-]+) s\)/\2/')"
    rss_mb="$(awk '{printf "%.0f", $1 / 1024}' "$out/rss.txt")"
    echo "$dofs,$p,$wall,$modes,$rss_mb,\"$machine\"" >> "$out/solid_scaling.csv"
    echo "$dofs DoFs on $p rank(s): $wall s (modes $modes s), $rss_mb MB"
  done
done
rm -f "$out/rss.txt"
/usr/bin/python3 scripts/plot_solid_scaling.py "$out/solid_scaling.csv" "$out/solid_scaling.png"
