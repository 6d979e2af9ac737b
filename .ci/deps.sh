#!/usr/bin/env bash
# Installs hgridlab's Debian packages when any is missing (needs root).
# Extra packages may be named as arguments (CI: `bash .ci/deps.sh clang`).
set -euo pipefail
pkgs=("$@"
      build-essential cmake libgsl-dev libhdf5-dev libbenchmark-dev libgtest-dev
      libcli11-dev libtomlplusplus-dev nlohmann-json3-dev gnuplot-nox
      jq  # plots/calibration.sh (make calibrate-figure) reads the tool's JSON
      lammps libcgal-dev)  # the peers comparison (bench/peers): LAMMPS at run time, CGAL's headers
                           # at build time; both optional, each skipped with a message when missing
missing=()
for p in "${pkgs[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "installing: ${missing[*]}" >&2
if [ "$(id -u)" -ne 0 ]; then
  echo "error: missing packages and not root; run: sudo apt-get install -y ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq "${missing[@]}"
