#!/usr/bin/env bash
# Installs the Debian packages beamslider needs (if missing) and builds it in
# ./build (Release). Safe to run again: apt-get and CMake skip what is done.
#
#   bash scripts/setup.sh           the `beamslider` program only (what the
#                                   README's first command needs)
#   bash scripts/setup.sh --tests   everything: also the GoogleTest programs,
#                                   the benchmarks and the Python module
#                                   (the second command, CI)
set -euo pipefail
cd "$(dirname "$0")/.."

target=(--target beamslider)
case "${1:-}" in
  "") ;;
  --tests) target=() ;;
  *) echo "setup.sh: unknown argument '$1' (allowed: none, or --tests)" >&2; exit 2 ;;
esac

packages=(cmake g++ make ccache libdeal.ii-dev libeigen3-dev libvtk9-dev libgtest-dev
          libbenchmark-dev libcli11-dev python3-matplotlib python3-numpy python3-dev
          pybind11-dev openmpi-bin python3-scipy python3-nbconvert python3-ipykernel)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing Debian packages: ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

if [ ${#target[@]} -gt 0 ]; then what="build/beamslider"; else what="build/beamslider, the tests, the benchmarks and the Python module"; fi
echo "== building $what (Release) in ./build"
source scripts/compiler_cache.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${compiler_cache[@]}" > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build build -j "$(nproc)" "${target[@]}" >> build.log 2>&1 || { tail -50 build.log; exit 1; }
echo "== built $what"
