#!/usr/bin/env bash
# Figures 11 and 12 (and the occupancy statistic): runs the scenes with the
# HGrid on generated packings, then draws paper_figs/fig11-*.png|pdf and
# fig12-*.png|pdf from the CSV results. Usage: plots/experiments.sh [SCALE]
set -euo pipefail
cd "$(dirname "$0")/.."
scale=${1:-default}
hgrid=${HGRID:-build/hgrid}
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}
suffix=$([ "$scale" = default ] && echo "" || echo "-$scale")
mkdir -p results paper_figs

for scene in fig11 fig12 occupancy; do
  "$hgrid" run "experiments/$scene.toml" --scale "$scale" --jobs "$jobs"
done

# plot SCRIPT CSV NAME: PNG and PDF, each written to a temporary name first.
plot() {
  local script=$1 csv=$2 name=$3
  for fmt in png pdf; do
    local out="paper_figs/$name$suffix.$fmt" tmp="paper_figs/.$name$suffix.tmp.$fmt"
    gnuplot -e "in='$csv'; out='$tmp'; fmt='$fmt'; scale_label='$scale scale'" "$script"
    mv -f "$tmp" "$out"
  done
  echo "wrote paper_figs/$name$suffix.png and .pdf" >&2
}
plot plots/fig11.gp "results/fig11$suffix.csv" fig11-measured-vs-model-nu
plot plots/fig12.gp "results/fig12$suffix.csv" fig12-measured-vs-model-n
