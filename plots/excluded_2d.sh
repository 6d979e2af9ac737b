#!/usr/bin/env bash
# The excluded-volume model in 2D against measured counts: hard-disc packings
# (periodic or walls, seed 1; cached under results/packings/), optimal Top-Down sizes
# of the paper's model (K = 0.2), T/N measured by `hgrid count` beside the
# paper's model and the excluded-volume model (docs/MODEL.md section 8:
# numerical Percus-Yevick solution for discs). Writes results/excluded-2d[-SCALE].csv
# and prints it as a Markdown table.
# Usage: plots/excluded_2d.sh [SCALE]   (default: 15 periodic points, N = 10^5 and one 10^6, and 8 walled ones,
#        N = 3000 to 10^5, ~2 min; smoke: 4 points)
set -euo pipefail
cd "$(dirname "$0")/.."
scale=${1:-default}
hgrid=${HGRID:-build/hgrid}
if ! command -v jq >/dev/null 2>&1; then
  echo "plots/excluded_2d.sh: jq is not installed (optional: apt-get install jq); skipped" >&2
  exit 0
fi
# dist alpha omega nu n boundary [sigma]
points_default="
powerlaw -3 2 0.2 100000 periodic
powerlaw -3 2 0.4 100000 periodic
powerlaw -3 2 0.6 100000 periodic
powerlaw -3 10 0.2 100000 periodic
powerlaw -3 10 0.4 100000 periodic
powerlaw -3 10 0.6 100000 periodic
powerlaw -3 20 0.2 100000 periodic
powerlaw -3 20 0.4 100000 periodic
powerlaw -3 20 0.6 100000 periodic
powerlaw -3 50 0.2 100000 periodic
powerlaw -3 50 0.4 100000 periodic
powerlaw 0 10 0.6 100000 periodic
powerlaw -2 20 0.5 100000 periodic
lognormal 0 10 0.5 100000 periodic 0.5
powerlaw -3 20 0.6 1000000 periodic
powerlaw -3 10 0.4 3000 walls
powerlaw -3 10 0.4 10000 walls
powerlaw -3 20 0.4 3000 walls
powerlaw -3 20 0.4 100000 walls
powerlaw 0 10 0.6 3000 walls
powerlaw -2 10 0.6 10000 walls
powerlaw -3 10 0.6 3000 walls
powerlaw -3 10 0.6 10000 walls"
points_smoke="
powerlaw -3 2 0.4 20000 periodic
powerlaw -3 10 0.6 20000 periodic
powerlaw -3 20 0.4 20000 periodic
powerlaw -3 10 0.4 3000 walls"
case "$scale" in smoke) points=$points_smoke ;; *) points=$points_default ;; esac
suffix=$([ "$scale" = default ] && echo "" || echo "-$scale")
mkdir -p results results/packings
csv=results/excluded-2d$suffix.csv
tmp=$csv.tmp.$$
trap 'rm -f "$tmp"' EXIT
{
  echo "# 2D excluded-volume (hard-disc) packings, seed 1: measured T/N (hgrid count, optimal Top-Down sizes, K = 0.2) against the paper's model and the excluded-volume model"
  echo "# error = measured / model - 1; seconds_count = wall time of hgrid count (mostly the excluded-volume model)"
  echo "# git_hash=$(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown) machine=$(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | cut -d: -f2 | sed 's/^ //' || echo unknown)"
  echo "dist,boundary,alpha,omega,sigma,nu,n,levels,T_over_N,model_T_over_N,model_excluded_T_over_N,error_paper,error_excluded,seconds_count"
  while read -r dist alpha omega nu n boundary sigma; do
    [ -z "$dist" ] && continue
    sigma=${sigma:-0.5}
    echo "plots/excluded_2d.sh: $dist alpha=$alpha omega=$omega nu=$nu n=$n $boundary" >&2
    f=$("$hgrid" generate --d 2 --n "$n" --nu "$nu" --dist "$dist" --alpha "$alpha" --omega "$omega" --sigma "$sigma" \
          --boundary "$boundary" --placement excluded --seed 1 --cache results/packings --quiet | tail -1)
    t0=$(date +%s.%N)
    j=$("$hgrid" count "$f" --cells optimal --threads 1 --json 2>/dev/null)
    t1=$(date +%s.%N)
    echo "$j" | jq -r --arg d "$dist" --arg a "$alpha" --arg w "$omega" --arg s "$sigma" --arg nu "$nu" \
      --arg sec "$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }')" \
      '[$d, .boundary, $a, $w, $s, $nu, .n, .levels, .T_over_N, .model_T_over_N, .model_excluded_T_over_N,
        (.T_over_N / .model_T_over_N - 1), (.T_over_N / .model_excluded_T_over_N - 1), $sec] | @csv' | tr -d '"'
  done <<< "$points"
} > "$tmp"
mv "$tmp" "$csv"
echo "| distribution | boundary | alpha | omega | nu | N | measured T/N | paper model | excluded-volume model |"
echo "|---|---|---|---|---|---|---|---|---|"
grep -v '^#' "$csv" | tail -n +2 | awk -F, '{d = $1 == "lognormal" ? "log-normal, sigma " $5 : "power law"; printf "| %s | %s | %s | %s | %s | %s | %.3f | %+.1f %% | %+.2f %% |\n", d, $2, ($1 == "lognormal" ? "-" : $3), $4, $6, $7, $9, 100 * $12, 100 * $13}'
