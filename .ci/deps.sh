#!/usr/bin/env bash
# Installs hgridlab's Debian packages when any is missing. As root, missing
# packages are installed (apt-get). As a normal user, a missing required
# package stops with the apt-get line to run; a missing optional one (LAMMPS,
# CGAL, Embree, Bullet, MPI, jq, doxygen) is skipped with a message. Extra packages may
# be named as arguments (CI: `bash .ci/deps.sh clang`); they count as required.
set -euo pipefail
required=("$@"
      build-essential cmake libgsl-dev libhdf5-dev libbenchmark-dev libgtest-dev
      libcli11-dev libtomlplusplus-dev nlohmann-json3-dev gnuplot-nox
      pybind11-dev python3-dev python3-numpy python3-pytest
      python3-setuptools python3-pybind11 python3-build python3-venv)  # pip install . (tests/python_install.sh)
optional=(jq          # plots/calibration.sh (make calibrate-figure) reads the tool's JSON
          doxygen     # make docs: the API reference (its test, Layout.ApiReference)
          lammps      # bench/peers at run time
          libcgal-dev libembree-dev libbullet-dev  # bench/peers at build time
          libopenmpi-dev openmpi-bin)  # hgrid under mpirun/srun, and its tests
missing() { local p; for p in "$@"; do dpkg -s "$p" >/dev/null 2>&1 || echo "$p"; done; }
mapfile -t miss_req < <(missing "${required[@]}")
mapfile -t miss_opt < <(missing "${optional[@]}")
[ ${#miss_req[@]} -eq 0 ] && [ ${#miss_opt[@]} -eq 0 ] && exit 0
if [ "$(id -u)" -ne 0 ]; then
  if [ ${#miss_opt[@]} -gt 0 ]; then
    echo "note: optional packages missing, their parts are skipped: ${miss_opt[*]}" >&2
  fi
  if [ ${#miss_req[@]} -gt 0 ]; then
    echo "error: missing packages and not root; run: sudo apt-get install -y ${miss_req[*]}" >&2
    exit 1
  fi
  exit 0
fi
echo "installing: ${miss_req[*]} ${miss_opt[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq "${miss_req[@]}"
if [ ${#miss_opt[@]} -gt 0 ]; then
  apt-get install -y -qq "${miss_opt[@]}" || echo "note: optional packages not installed, their parts are skipped: ${miss_opt[*]}" >&2
fi
