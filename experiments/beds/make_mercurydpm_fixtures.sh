#!/usr/bin/env bash
# Pours the MercuryDPM beds of tests/data/beds (bench/mercurydpm/pour.cpp,
# built by bench/mercurydpm/build.sh) and keeps two snapshots of each .data
# file: a gas falling onto a forming bed (t = 4) and the settled bed
# (t = 24). The box is walled on every side (the .data file does not say
# so; the tests set it). About 10 minutes on one core.
#   MERCURYDPM_BUILD=build-mercurydpm experiments/beds/make_mercurydpm_fixtures.sh [OUTDIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-$here/../../tests/data/beds}
driver=${MERCURYDPM_BUILD:-build-mercurydpm}/drivers/mercurydpm_pour
[ -x "$driver" ] || { echo "make_mercurydpm_fixtures.sh: $driver not built (bench/mercurydpm/build.sh)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pour() {  # name d n dlo dhi seed
  local name=$1
  echo "pouring $name with MercuryDPM ($3 particles, d = $2, diameters $4-$5, seed $6)" >&2
  "$driver" "$work" "$@" >"$work/$name.log" 2>&1
  # Snapshots every 2 time units from t = 0, each a header (N first) and N
  # particle lines: keep the 3rd (t = 4) and the last.
  awk -v d="$2" '
    NF == (d == 3 ? 8 : 6) && left == 0 { f++; left = $1; block[f] = $0 "\n"; next }
    { block[f] = block[f] $0 "\n"; left-- }
    END { printf "%s%s", block[3], block[f] }
  ' "$work/$name.data" > "$out/$name.data.tmp"
  mv "$out/$name.data.tmp" "$out/$name.data"
}
mkdir -p "$out"
pour mdpm3d_o5_s1 3 3000 0.2 1.0 1
pour mdpm2d_o10_s2 2 2000 0.1 1.0 2
echo "wrote $out/mdpm*.data" >&2
