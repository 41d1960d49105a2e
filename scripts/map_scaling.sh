#!/usr/bin/env bash
# Strong scaling of `beamslider map`: the same map (default 24 cells of the
# ROM, 10 s each) on 1, 2, … ranks, written as scaling.csv and drawn by
# plot_map_scaling.py as map_scaling.png in the output folder.
#     bash scripts/map_scaling.sh [OUTPUT_DIR] [MAX_RANKS]
# Run from the repository root after building. As root (a container), Open
# MPI needs OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1.
set -euo pipefail
out="${1:-reports/mueller2023/map_scaling}"
max_ranks="${2:-$(nproc)}"
program="build/beamslider"
[[ -x "$program" ]] || { echo "map_scaling.sh: $program not found; build first" >&2; exit 1; }
mkdir -p "$out"
machine="$(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
echo "ranks,cells,wall_s,cells_per_s,machine" > "$out/scaling.csv"
args=(map mueller2023 --frequency 100:135:5 --acceleration 8:18:5 --end-time 10)
for ((p = 1; p <= max_ranks; p *= 2)); do
  dir="$out/ranks_$p"
  rm -rf "$dir"
  if ((p == 1)); then
    log="$("$program" "${args[@]}" --output "$dir")"
  else
    log="$(mpirun -np "$p" "$program" "${args[@]}" --output "$dir")"
  fi
  # The command's last line: "map: N cells in W s on P rank(s); …"
  line="$(grep '^map: ' <<< "$log" | tail -1)"
  cells="$(awk '{print $2}' <<< "$line")"
  wall="$(awk '{print $5}' <<< "$line")"
  echo "$p,$cells,$wall,,\"$machine\"" >> "$out/scaling.csv"
  echo "ranks $p: $cells cells in $wall s"
done
/usr/bin/python3 scripts/plot_map_scaling.py "$out/scaling.csv" "$out/map_scaling.png"
