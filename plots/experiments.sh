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

# One pool for the three scenes: no core waits for one scene's last packing
# while another has work left, and the packing figure 11 and the occupancy
# scene share is made once.
"$hgrid" run experiments/fig11.toml experiments/fig12.toml experiments/occupancy.toml --scale "$scale" --jobs "$jobs"

# values CSV COLUMN: the distinct values of a column, ascending, space separated.
values() {
  awk -F, -v col="$2" '/^#/ {next} !h {for (i = 1; i <= NF; i++) if ($i == col) c = i; h = 1; next}
    {print $c + 0}' "$1" | sort -g -u | tr '\n' ' '
}

# plot SCRIPT CSV NAME SERIES: PNG and PDF, each written to a temporary name first.
plot() {
  local script=$1 csv=$2 name=$3 series=$4
  for fmt in png pdf; do
    local out="paper_figs/$name$suffix.$fmt" tmp="paper_figs/.$name$suffix.tmp.$fmt"
    gnuplot -e "in='$csv'; out='$tmp'; fmt='$fmt'; scale_label='$scale scale'; series='$series'" "$script"
    if [ "$fmt" = pdf ]; then plots/lib/pdf_fixdate.sh "$tmp"; fi  # a fixed date: same data, same bytes
    mv -f "$tmp" "$out"
  done
  echo "wrote paper_figs/$name$suffix.png and .pdf" >&2
}
plot plots/fig11.gp "results/fig11$suffix.csv" fig11-measured-vs-model-nu "$(values "results/fig11$suffix.csv" omega)"
plot plots/fig12.gp "results/fig12$suffix.csv" fig12-measured-vs-model-n "$(values "results/fig12$suffix.csv" alpha | tr ' ' '\n' | sort -gr | tr '\n' ' ')"
if [ -f "results/fig12_growth$suffix.csv" ]; then  # `hgrid run experiments/fig12_growth.toml` (not run here)
  plot plots/fig12.gp "results/fig12_growth$suffix.csv" fig12-growth-measured-vs-model-n \
    "$(values "results/fig12_growth$suffix.csv" alpha | tr ' ' '\n' | sort -gr | tr '\n' ' ')"
fi
bash plots/model_errors.sh "$scale"
# The ghost counts (mostly mpirun start-up, half a core) beside the other
# count-only figures: nothing here is timed, so they may share the cores.
bash plots/ghosts.sh "$scale" &   # the decomposed search's ghosts (skipped without MPI)
ghosts=$!
bash plots/excess_by_level.sh "$scale"
bash plots/slice_by_level.sh "$scale"
bash plots/balance.sh "$scale"
wait "$ghosts"
