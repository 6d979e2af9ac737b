#!/usr/bin/env bash
# Pours the beds of tests/data/beds with LAMMPS (Debian's `lammps`, lmp) and
# keeps two frames of each: one in progress (a gas over a bed) and the
# settled bed. About 5 minutes on one core. Usage: make_fixtures.sh [OUTDIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-$here/../../tests/data/beds}
command -v lmp >/dev/null || { echo "make_fixtures.sh: lmp (LAMMPS) not found; apt-get install lammps" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pour() {  # name script n dlo dhi seed steps every dt frames
  local name=$1 script=$2 n=$3 dlo=$4 dhi=$5 seed=$6 steps=$7 every=$8 dt=$9 keep=${10}
  echo "pouring $name ($n particles, diameters $dlo-$dhi, seed $seed)" >&2
  (cd "$work" && lmp -in "$here/$script" -var n "$n" -var dlo "$dlo" -var dhi "$dhi" -var seed "$seed" \
     -var out "$name.dump" -var steps "$steps" -var every "$every" -var dt "$dt" -log "$name.log" -screen none)
  # The frames kept (0-based), in the order LAMMPS wrote them.
  awk -v keep="$keep" 'BEGIN { n = split(keep, k, ","); for (i = 1; i <= n; ++i) want[k[i]] = 1 }
       /^ITEM: TIMESTEP/ { f++ } want[f - 1] { print }' "$work/$name.dump" > "$out/$name.dump.tmp"
  mv "$out/$name.dump.tmp" "$out/$name.dump"
}
mkdir -p "$out"
pour bed3d_o5_s1  in.bed3d 3000 0.2  1.0 12345 250000 25000 0.0004 4,10
pour bed3d_o3_s2  in.bed3d 2500 0.33 1.0 99    250000 25000 0.0004 2,10
pour bed2d_o5_s1  in.bed2d 2000 0.2  1.0 777   250000 25000 0.0004 4,10
pour bed2d_o10_s2 in.bed2d 2000 0.1  1.0 4242  500000 50000 0.0002 4,10
echo "wrote $out/bed*.dump" >&2
