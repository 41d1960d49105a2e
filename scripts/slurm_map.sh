#!/usr/bin/env bash
# Slurm batch script: the operating map of the mueller2023 scene (frequency
# 95..135 Hz in 2.5 Hz steps, base acceleration 4..20 m/s² in 1 m/s² steps,
# 4 ensemble members per cell) on 2 nodes x 32 MPI ranks.
# Submit from the repository root (after building into ./build):
#     sbatch scripts/slurm_map.sh
#
# How it runs: every rank computes cells; rank 0 also hands out the cells
# one by one to whichever rank is free, and each finished cell (all its
# members) is appended to reports/mueller2023/map/map.csv at once, so the
# file holds every cell finished so far.
# After a kill or a time-out (--time below), re-submit the same command
# unchanged: finished cells in map.csv are skipped and only the others are
# computed (a cell cut short is computed again). The settings must match the
# first run (map_settings.txt in the output folder), so do not change the
# grid, members or scene between submissions.
# Afterwards: /usr/bin/python3 scripts/plot_map.py reports/mueller2023/map "mueller2023"
#
#SBATCH --job-name=beamslider-map
#SBATCH --nodes=2
#SBATCH --ntasks-per-node=32
#SBATCH --cpus-per-task=1
#SBATCH --time=04:00:00
#SBATCH --output=beamslider-map-%j.out
set -euo pipefail

cd "${SLURM_SUBMIT_DIR:-.}"
if [[ ! -x build/beamslider ]]; then
  echo "slurm_map.sh: build/beamslider not found in $(pwd); submit from the repository root after building" >&2
  exit 1
fi
mkdir -p reports/mueller2023/map

# One thread per rank (the ranks already fill the cores).
export OMP_NUM_THREADS=1

args=(map mueller2023 --frequency 95:135:2.5 --acceleration 4:20:1 --members 4
      --output reports/mueller2023/map)

# srun starts one task per Slurm task; --mpi=pmix lets Open MPI find its
# peers (check `srun --mpi=list` on your cluster). Without a PMIx-enabled
# Slurm, use Open MPI's launcher instead, which reads the allocation itself:
#     mpirun -np "$SLURM_NTASKS" build/beamslider "${args[@]}"
# or, outside Slurm, with a hostfile (see scripts/map_hostfile.example):
#     mpirun --hostfile my_hostfile -np 64 build/beamslider "${args[@]}"
srun --mpi=pmix build/beamslider "${args[@]}"
