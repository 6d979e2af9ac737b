#!/usr/bin/env bash
# A slice through one figure-11 packing (alpha = -3, omega = 100, nu = 0.6,
# excluded volume) with every particle cut by the plane z = A/2 drawn as its
# section, coloured by its level of insertion in the grid `hgrid recommend`
# gives (K = 0.2). Writes results/slice-by-level[-SCALE].csv and
# paper_figs/slice-by-level[-SCALE].png|pdf. Usage: plots/slice_by_level.sh [SCALE]
# (default: N = 10^5; paper: 10^6; smoke: 3*10^4)
set -euo pipefail
cd "$(dirname "$0")/.."
scale=${1:-default}
hgrid=${HGRID:-build/hgrid}
case "$scale" in smoke) n=30000 ;; paper) n=1000000 ;; *) n=100000 ;; esac
suffix=$([ "$scale" = default ] && echo "" || echo "-$scale")
csv="results/slice-by-level$suffix.csv"
mkdir -p results paper_figs results/packings
packing=$("$hgrid" generate --n "$n" --nu 0.6 --omega 100 --alpha -3 --placement excluded --seed 1 \
          --cache results/packings --quiet | tail -1)
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
for fmt in png pdf; do
  out="paper_figs/slice-by-level$suffix.$fmt" t="paper_figs/.slice-by-level$suffix.tmp.$fmt"
  gnuplot -e "in='$csv'; out='$t'; fmt='$fmt'; n='$n'; levels=$levels; box=$box" plots/slice_by_level.gp
  if [ "$fmt" = pdf ]; then plots/lib/pdf_fixdate.sh "$t"; fi
  mv -f "$t" "$out"
done
echo "wrote $csv and paper_figs/slice-by-level$suffix.png|pdf" >&2
