#!/usr/bin/env bash
# The sheared packing of tests/data/beds/shear3d_o5.dump: a dense
# polydisperse packing made by hgrid (N = 4000, nu = 0.55, radii uniform in
# [1, 5], periodic), sheared by LAMMPS (in.shear3d: Lees-Edwards, xy growing
# at rate 0.01, velocities remapped) to a strain of 0.5, where the tilt is
# LAMMPS's limit xy = lx / 2. About 10 s. Usage: make_fixture.sh [BUILD_DIR] [OUTDIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../build}" && pwd)
out=${2:-$here/../../tests/data/beds}
command -v lmp >/dev/null || { echo "make_fixture.sh: lmp (LAMMPS) not found; apt-get install lammps" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
"$build/hgrid" export --lammps . --n 4000 --nu 0.55 --alpha 0 --omega 5 --boundary periodic --seed 7 \
  --cache "$work/cache" >/dev/null
lmp -in "$here/in.shear3d" -var data data.lmp -var out shear.dump -var steps 5000 -var every 5000 \
  -log log.shear -screen none
# Frames at steps 0 and 5000: keep the second (strain 0.5).
awk '/^ITEM: TIMESTEP/ { f++ } f == 2 { print }' shear.dump > "$out/shear3d_o5.dump.tmp"
mv "$out/shear3d_o5.dump.tmp" "$out/shear3d_o5.dump"
echo "wrote $out/shear3d_o5.dump" >&2
