#!/usr/bin/env bash
# Where the excluded-volume excess comes from: narrow-phase checks per level
# (measured, the paper's model, the excluded-volume model) for alpha = -3,
# omega = 100, nu = 0.6, optimal Top-Down sizes. Writes
# results/excess-by-level[-SCALE].csv and paper_figs/excess-by-level[-SCALE].png|pdf.
# Usage: plots/excess_by_level.sh [SCALE]   (default: N = 10^5; paper: 10^6; smoke: 3*10^4, the smallest box that holds 4 r_max)
set -euo pipefail
cd "$(dirname "$0")/.."
source plots/lib/fig11_packing.sh "${1:-default}"
csv="results/excess-by-level$suffix.csv"
tmp="$csv.tmp.$$"
{
  echo "# excess by level: alpha=-3 omega=100 nu=0.6 n=$n seed=1 placement=excluded; checks per particle (all levels searched)"
  echo "level,size,particles,measured,paper_model,excluded_model"
  "$hgrid" count "$packing" --cells optimal |
    awk -v n="$n" '$1 ~ /^[0-9]+$/ && NF == 7 {printf "%d,%.6g,%d,%.6g,%.6g,%.6g\n", $1, $2, $3, $5 / n, $6 / n, $7 / n}'
} > "$tmp"
mv -f "$tmp" "$csv"
draw excess-by-level plots/excess_by_level.gp "$csv"
