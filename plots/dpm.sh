#!/usr/bin/env bash
# The paper's full DPM test (Sect. 5): runs experiments/dpm_free_cooling.toml
# at a scale (timed runs: hold the machine-wide build lock if others build),
# then draws paper_figs/fig14-dpm-energy*.png|pdf and renders the table
# paper_figs/fig14-dpm-table*.md from the run's CSV ("# key=value" lines),
# beside the paper's numbers (Sect. 5.5: predicted speed-up ~35, measured
# whole-run speed-up 9.9). Usage: plots/dpm.sh [SCALE]
set -euo pipefail
cd "$(dirname "$0")/.."
scale=${1:-default}
hgrid=${HGRID:-build/hgrid}
suffix=$([ "$scale" = default ] && echo "" || echo "-$scale")
mkdir -p results paper_figs

# DPM_PLOT_ONLY=1 redraws from existing results without running.
if [ "${DPM_PLOT_ONLY:-0}" = 0 ]; then
  "$hgrid" run experiments/dpm_free_cooling.toml --scale "$scale"
fi

csv="results/dpm_free_cooling$suffix.csv"
# The value of one "# key=value" line of the CSV.
val() { sed -n "s/^# $1=//p" "$csv" | head -n 1; }
n=$(val n)
for fmt in png pdf; do
  out="paper_figs/fig14-dpm-energy$suffix.$fmt" tmp="paper_figs/.fig14-dpm-energy$suffix.tmp.$fmt"
  gnuplot -e "in='$csv'; out='$tmp'; fmt='$fmt'; scale_label='$scale scale'; n_label='$n'" plots/fig14.gp
  if [ "$fmt" = pdf ]; then plots/lib/pdf_fixdate.sh "$tmp"; fi  # a fixed date: same data, same bytes
  mv -f "$tmp" "$out"
done
table="paper_figs/fig14-dpm-table$suffix.md"
paper_cd=35 paper_total=9.9  # the paper's predicted CD speed-up and measured whole-run speed-up
f1() { awk -v x="$1" 'BEGIN { printf "%.1f", x }'; }
sizes=$(val optimal.sizes | awk -F';' '{ for (i = 1; i <= NF; i++) printf "%s%.1f", (i > 1 ? ", " : ""), $i }')
{
  echo "| scale | N | steps | optimal sizes (r_min) | wall time optimal / linked cell | predicted CD speed-up (K = 0.2) | measured count ratio | predicted CD speed-up (time model) | measured CD speed-up | whole-run speed-up | Haff fit r^2 | contact list over the optimal grid rebuilt every step: CD / whole run (skin) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
  echo "| $scale | $n | $(val steps) | $(val optimal.levels) levels: $sizes | $(f1 "$(val optimal.seconds_total)") s / $(f1 "$(val linked_cell.seconds_total)") s | $(f1 "$(val predicted_speedup_contact_detection)") (paper $paper_cd) | $(f1 "$(val measured_count_ratio)") | $(t=$(val predicted_speedup_seconds); [ -n "$t" ] && f1 "$t" || echo "— (no calibration)") | $(f1 "$(val speedup_contact_detection)") | $(f1 "$(val speedup_total)") (paper $paper_total) | $(awk -v x="$(val haff.r2)" 'BEGIN { printf "%.4f", x }') | $(l=$(val speedup_list_contact_detection); [ -n "$l" ] && echo "$(f1 "$l") / $(f1 "$(val speedup_list_total)") ($(val skin) r_min)" || echo "—") |"
} > "$table.tmp"
mv -f "$table.tmp" "$table"
echo "wrote paper_figs/fig14-dpm-energy$suffix.png and .pdf, $table" >&2
