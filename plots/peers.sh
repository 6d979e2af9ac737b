#!/usr/bin/env bash
# hgridlab vs peers on the figure-11 packings (nu = 0.1 ... 0.6), one bench/peers
# run per packing, collected in results/peers.csv and drawn as paper_figs/peers.png.
#   bash plots/peers.sh [N] [placement]      (default N = 100000, excluded: ~15 min;
#                                           N = 1000000: about an hour)
# PEERS_FLAGS (default: no linked cell, which takes ~50 s per build at N = 1e5,
# and the small LAMMPS class scan) is passed on to build/peers.
# PEERS_PLOT_ONLY=1 redraws paper_figs/peers.png from results/peers.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
N=${1:-100000}
PLACEMENT=${2:-excluded}
FLAGS=${PEERS_FLAGS:---no-linked-cell --scan small}
CSV=results/peers.csv
mkdir -p results/peers paper_figs
if [ "${PEERS_PLOT_ONLY:-0}" != 0 ]; then
  gnuplot -e "in='$CSV'; out='paper_figs/.peers.tmp.png'; placement='$PLACEMENT'" plots/peers.gp
  mv -f paper_figs/.peers.tmp.png paper_figs/peers.png
  echo "redrew paper_figs/peers.png from $CSV"
  exit 0
fi
# Every output goes to a temporary name first and is renamed when complete:
# a failed or interrupted run leaves the previous results as they were.
tmp_csv="results/.peers.csv.tmp"
trap 'rm -f "$tmp_csv" results/peers/*.json.tmp paper_figs/.peers.tmp.png' EXIT
rm -f "$tmp_csv"
for nu in 0.1 0.2 0.3 0.4 0.5 0.6; do
  json="results/peers/n${N}-nu${nu}-${PLACEMENT}.json"
  build/peers --n "$N" --nu "$nu" --placement "$PLACEMENT" --csv "$tmp_csv" --json $FLAGS > "$json.tmp"
  mv -f "$json.tmp" "$json"
done
gnuplot -e "in='$tmp_csv'; out='paper_figs/.peers.tmp.png'; placement='$PLACEMENT'" plots/peers.gp
mv -f "$tmp_csv" "$CSV"
mv -f paper_figs/.peers.tmp.png paper_figs/peers.png
echo "wrote $CSV and paper_figs/peers.png"
