#!/usr/bin/env bash
# hgridlab and its peers against N on 1 and THREADS threads (bench/peers
# --threads: hgridlab's and Embree's threads, LAMMPS's MPI ranks; Bullet has
# one), on the figure-11 packing (3D, periodic, alpha = -3, omega = 100,
# nu = 0.6, excluded volume; cached under results/packings/). LAMMPS bin is
# left out at N >= 10^6 (minutes per build). Writes results/peers/threads-*.json,
# results/peers-threads.csv and paper_figs/peers-threads.png.
# Usage: bash plots/peers_threads.sh [THREADS] [N...]   (default 2; N = 3e4 (the smallest box that
# holds 4 r_max), 1e5, 1e6: ~15 min)
set -euo pipefail
cd "$(dirname "$0")/.."
threads=${1:-2}
shift || true
ns=${*:-30000 100000 1000000}
if ! command -v jq >/dev/null 2>&1; then
  echo "plots/peers_threads.sh: jq is not installed (optional: apt-get install jq); skipped" >&2
  exit 0
fi
mkdir -p results/peers paper_figs
csv=results/peers-threads.csv
tmp=$csv.tmp.$$
trap 'rm -f "$tmp" results/peers/*.json.tmp' EXIT
echo "n,threads,tool,tool_threads,seconds_per_particle,pairs,ratio_vs_hgrid" > "$tmp"
for n in $ns; do
  for t in 1 "$threads"; do
    flags=""
    if [ "$n" -ge 1000000 ]; then flags="--no-bin"; fi
    json="results/peers/threads${t}-n${n}.json"
    build/peers --n "$n" --threads "$t" $flags --json > "$json.tmp"
    mv -f "$json.tmp" "$json"
    jq -r --arg t "$t" '. as $j | ["hgrid", "lammps_multi", "lammps_bin", "cgal", "embree", "bullet"][] as $k |
        select($j[$k] != null) |
        [$j.n, $t, $k,
         (if $k == "bullet" or $k == "cgal" then 1 else ($t | tonumber) end),
         $j[$k].seconds_per_particle, $j[$k].pairs, (if $k == "hgrid" then 1 else $j["ratio_vs_" + $k] end)] | @csv' \
      "$json" | tr -d '"' >> "$tmp"
    echo "peers_threads: n=$n threads=$t done" >&2
  done
done
mv -f "$tmp" "$csv"
gnuplot -e "in='$csv'; out='paper_figs/.peers-threads.tmp.png'; threads=$threads" plots/peers_threads.gp
mv -f paper_figs/.peers-threads.tmp.png paper_figs/peers-threads.png
echo "wrote $csv and paper_figs/peers-threads.png" >&2
