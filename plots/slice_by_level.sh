#!/usr/bin/env bash
# A slice through one figure-11 packing (alpha = -3, omega = 100, nu = 0.6,
# excluded volume) with every particle cut by the plane z = A/2 drawn as its
# section, coloured by its level of insertion in the grid `hgrid recommend`
# gives (K = 0.2). Writes results/slice-by-level[-SCALE].csv and
# paper_figs/slice-by-level[-SCALE].png|pdf. Usage: plots/slice_by_level.sh [SCALE]
# (default: N = 10^5; paper: 10^6; smoke: 3*10^4)
set -euo pipefail
cd "$(dirname "$0")/.."
source plots/lib/fig11_packing.sh "${1:-default}"
csv="results/slice-by-level$suffix.csv"
xyz="results/.slice$suffix.tmp.$$.xyz"
trap 'rm -f "$xyz" "$csv.tmp.$$"' EXIT
"$hgrid" export "$packing" --xyz "$xyz" --K 0.2 > /dev/null
box=$(awk 'NR == 2 {match($0, /Lattice="[^ "]*/); print substr($0, RSTART + 9, RLENGTH - 9); exit}' "$xyz")
levels=$("$hgrid" recommend "$packing" --K 0.2 --json | awk -F: '/"levels"/ {gsub(/[ ,]/, "", $2); print $2}')
# The extended XYZ: line 2 holds the box (Lattice="A 0 0 0 A 0 0 0 A"); then
# "P x y z r level cell". A particle is cut by the plane when |z - A/2| < r.
{
  echo "# slice z = A/2 of $packing (n=$n); section radius = sqrt(r^2 - (z - A/2)^2)"
  echo "x,y,section_radius,level"
  awk 'NR == 2 {match($0, /Lattice="[^"]*"/); split(substr($0, RSTART + 9, RLENGTH - 10), L, " "); h = L[9] / 2; next}
       NR > 2 {dz = $4 - h; if (dz * dz < $5 * $5) printf "%.9g,%.9g,%.9g,%d\n", $2, $3, sqrt($5 * $5 - dz * dz), $6}' "$xyz"
} > "$csv.tmp.$$"
mv -f "$csv.tmp.$$" "$csv"
draw slice-by-level plots/slice_by_level.gp "$csv" "levels=$levels; box=$box"
