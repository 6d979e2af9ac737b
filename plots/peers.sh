#!/usr/bin/env bash
# hgridlab vs peers on the figure-11 packings (nu = 0.1 ... 0.6), one bench/peers
# run per packing, collected in results/peers.csv and drawn as paper_figs/peers.png.
#   bash plots/peers.sh [N] [placement]      (default N = 100000, excluded: ~15 min;
#                                           N = 1000000: about an hour)
# PEERS_FLAGS (default: no linked cell, which takes ~50 s per build at N = 1e5,
# and the small LAMMPS class scan) is passed on to build/peers.
# PEERS_PLOT_ONLY=1 redraws paper_figs/peers.png from results/peers.csv.
# PEERS_MERCURYDPM=1 runs MercuryDPM's HGrid alone (needs MERCURYDPM_BUILD,
# bench/mercurydpm/build.sh; ~2 min at N = 1e5) into results/peers-mercurydpm.csv,
# then redraws; the figure shows that CSV's MercuryDPM rows when it exists.
set -euo pipefail
cd "$(dirname "$0")/.."
N=${1:-100000}
PLACEMENT=${2:-excluded}
FLAGS=${PEERS_FLAGS:---no-linked-cell --scan small}
CSV=results/peers.csv
MCSV=results/peers-mercurydpm.csv
mkdir -p results/peers paper_figs
draw() {  # draw CSV OUT: the peers of CSV and, when present, MercuryDPM's rows
  local extra=""
  [ -f "$MCSV" ] && extra="; in2='$MCSV'"
  gnuplot -e "in='$1'; out='$2'; placement='$PLACEMENT'$extra" plots/peers.gp
}
if [ "${PEERS_MERCURYDPM:-0}" != 0 ]; then
  [ -n "${MERCURYDPM_BUILD:-}" ] || { echo "peers.sh: set MERCURYDPM_BUILD (bench/mercurydpm/build.sh)" >&2; exit 2; }
  tmp="results/.peers-mercurydpm.csv.tmp"
  rm -f "$tmp"
  for nu in 0.1 0.2 0.3 0.4 0.5 0.6; do
    json="results/peers/mercurydpm-n${N}-nu${nu}-${PLACEMENT}.json"
    build/peers --n "$N" --nu "$nu" --placement "$PLACEMENT" --csv "$tmp" --json --no-linked-cell --no-lammps \
      --no-cgal --no-embree --no-bullet > "$json.tmp"
    mv -f "$json.tmp" "$json"
  done
  mv -f "$tmp" "$MCSV"
  PEERS_PLOT_ONLY=1
fi
if [ "${PEERS_PLOT_ONLY:-0}" != 0 ]; then
  draw "$CSV" paper_figs/.peers.tmp.png
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
draw "$tmp_csv" paper_figs/.peers.tmp.png
mv -f "$tmp_csv" "$CSV"
mv -f paper_figs/.peers.tmp.png paper_figs/peers.png
echo "wrote $CSV and paper_figs/peers.png"
