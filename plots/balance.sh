#!/usr/bin/env bash
# Load balance of the threaded query beyond this machine, by simulation
# (`hgrid count --balance`, src/measure/balance.hpp): for the figure-11
# packings (3D, periodic, alpha = -3, omega = 2..100, nu = 0.1..0.6, excluded
# volume as experiments/fig11.toml makes it and random centres; cached under
# results/packings/), optimal
# Top-Down sizes, the counted work of every piece of the query's
# decomposition for P = 8, 64 and 256 threads, handed out as the dynamic
# schedule does. Writes results/balance[-SCALE].csv and
# paper_figs/balance[-SCALE].png|pdf.
# Usage: plots/balance.sh [SCALE]   (default N = 10^5, paper 10^6, smoke 2*10^4)
set -euo pipefail
cd "$(dirname "$0")/.."
scale=${1:-default}
hgrid=${HGRID:-build/hgrid}
if ! command -v jq >/dev/null 2>&1; then
  echo "plots/balance.sh: jq is not installed (optional: apt-get install jq); load-balance figure skipped" >&2
  exit 0
fi
case "$scale" in smoke) n=20000; omegas="10 100"; nus="0.1 0.3 0.5" ;;
                 paper) n=1000000; omegas="2 10 50 100"; nus="0.1 0.2 0.3 0.4 0.5 0.6" ;;
                 *) n=100000; omegas="2 10 50 100"; nus="0.1 0.2 0.3 0.4 0.5 0.6" ;; esac
suffix=$([ "$scale" = default ] && echo "" || echo "-$scale")
source plots/lib/fig11_protocol.sh "$scale"
threads=8,64,256
mkdir -p results results/packings paper_figs
csv=results/balance$suffix.csv
tmp=$csv.tmp.$$
work=$(mktemp -d)
trap 'rm -rf "$tmp" "$work"' EXIT
# case_rows PLACEMENT OMEGA NU OUT: one packing's CSV rows into OUT. Counts
# only (no times), so the cases run side by side, JOBS at a time (default:
# the cores), each on one thread; the rows are joined in the loops' order.
case_rows() {
  local placement=$1 omega=$2 nu=$3 out=$4 args f
  args=$([ "$placement" = excluded ] && excluded_args "$omega" || true)
  # shellcheck disable=SC2086  # args: several options
  f=$("$hgrid" generate --d 3 --n "$n" --nu "$nu" --alpha -3 --omega "$omega" --placement "$placement" $args \
        --seed 1 --cache results/packings --quiet | tail -1)
  "$hgrid" count "$f" --cells optimal --threads 1 --model none --balance "$threads" --json |
    jq -r --arg pl "$placement" --arg w "$omega" --arg nu "$nu" \
      '.balance_cost as $c | .n as $n | .balance[] |
       [$pl, $w, $nu, $n, .threads, .pieces, .imbalance, .largest_piece, $c] | @csv' | tr -d '"' > "$out"
}
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}
pids=() k=0
for placement in excluded random; do
  for omega in $omegas; do
    for nu in $nus; do
      case_rows "$placement" "$omega" "$nu" "$work/$(printf %04d $k)" &
      pids+=($!) k=$((k + 1))
      if [ "${#pids[@]}" -ge "$jobs" ]; then wait "${pids[0]}"; pids=("${pids[@]:1}"); fi
    done
  done
done
for p in "${pids[@]}"; do wait "$p"; done
{
  echo "# simulated load balance of the threaded query (hgrid count --balance $threads): alpha=-3 d=3 periodic n=$n seed=1, optimal Top-Down sizes, K=0.2"
  echo "# imbalance = simulated time / (total work / P) - 1; largest_piece = largest piece / (total work / P)"
  echo "# git_hash=$(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)"
  echo "placement,omega,nu,n,threads,pieces,imbalance,largest_piece,cost"
  cat "$work"/*
} > "$tmp"
mv -f "$tmp" "$csv"
for fmt in png pdf; do
  out="paper_figs/balance$suffix.$fmt" t="paper_figs/.balance$suffix.tmp.$fmt"
  gnuplot -e "in='$csv'; out='$t'; fmt='$fmt'; n='$n'; omegas='$omegas'" plots/balance.gp
  if [ "$fmt" = pdf ]; then plots/lib/pdf_fixdate.sh "$t"; fi
  mv -f "$t" "$out"
done
echo "wrote $csv and paper_figs/balance$suffix.png|pdf" >&2
awk -F, '/^#/ || !h++ {next} {k = $5; if ($7 > w[k]) {w[k] = $7; at[k] = $1 " omega=" $2 " nu=" $3}}
  END {for (k in w) printf "balance: %s threads: worst simulated imbalance %.2f %% (%s)\n", k, 100 * w[k], at[k]}' "$csv" |
  sort -n -k2 >&2
