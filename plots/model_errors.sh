#!/usr/bin/env bash
# Tables of both models' errors at every excluded-volume point of Figs. 11
# and 12: measured T/N, and measured / predicted - 1 for the paper's model
# (random centres) and the excluded-volume model. Reads results/fig11[-S].csv,
# fig12[-S].csv and, if there, the as-placed fig11_placed[-S].csv and
# fig12_placed[-S].csv, fig11_equilibrated[-S].csv,
# fig12_equilibrated[-S].csv, fig12_growth[-S].csv and the compressed,
# then equilibrated fig11_growth_equilibrated[-S].csv,
# fig12_growth_equilibrated[-S].csv and fig12_large_equilibrated[-S].csv; writes
# paper_figs/model-errors[-S].md.
# Usage: plots/model_errors.sh [SCALE]
set -euo pipefail
cd "$(dirname "$0")/.."
scale=${1:-default}
suffix=$([ "$scale" = default ] && echo "" || echo "-$scale")
out="paper_figs/model-errors$suffix.md" tmp="paper_figs/.model-errors$suffix.tmp.md"
table() {  # CSV TITLE: one row per excluded-volume point
  awk -F, -v title="$2" '
    /^#/ { if (!hdr) prov = $0; next }
    !hdr { for (i = 1; i <= NF; i++) c[$i] = i; hdr = 1
           print "### " title "\n"; print "| boundary | alpha | omega | nu | N | packing | measured T/N | paper model | excluded-volume model |"
           print "|---|---|---|---|---|---|---|---|---|"; next }
    $c["placement"] == "excluded" {
      m = $c["T_over_N"]; p = $c["model_T_over_N"]; e = ("model_excluded_T_over_N" in c) ? $c["model_excluded_T_over_N"] : "NaN"
      pe = 100 * (m / p - 1); ee = (e == "NaN" || e == "") ? "-" : sprintf("%+.1f %%", 100 * (m / e - 1))
      # how the packing was made: the method and the Monte Carlo sweeps (CSVs written since they are columns)
      how = "-"
      if ("method" in c) {
        how = ($c["method"] == "growth") ? "compressed" : "placed"
        if ($c["equilibration_sweeps"] > 0) how = how sprintf(" + %d sweeps", $c["equilibration_sweeps"])
      }
      printf "| %s | %g | %g | %g | %d | %s | %.3f | %+.1f %% | %s |\n", $c["boundary"], $c["alpha"], $c["omega"], $c["nu"], $c["n"], how, m, pe, ee
      if (ee != "-") { a = m / e - 1; if (a < 0) a = -a; if (a > worst[$c["boundary"]]) worst[$c["boundary"]] = a }
      a = m / p - 1; if (a < 0) a = -a; if (a > pworst[$c["boundary"]]) pworst[$c["boundary"]] = a
    }
    END { print ""; if (!("model_excluded_T_over_N" in c)) print "(These results predate the excluded-volume model: rerun the scene to fill its column.)\n"
          for (b in pworst) printf "Largest |measured/predicted - 1|, %s: paper model %.1f %%%s.\n", b, 100 * pworst[b], (b in worst) ? sprintf(", excluded-volume model %.1f %%", 100 * worst[b]) : ""
          print "\nSource: " prov "\n" }' "$1"
}
{
  echo "# Model errors at every excluded-volume point ($scale scale)"
  echo
  echo "Entries are measured / predicted - 1 for T/N (K = 0.2), each model evaluated"
  echo "for the packing's own radii, packing fraction and the cell sizes used."
  echo "Packing: placed (largest-first sequential addition, growth + FIRE where it"
  echo "stalls) or compressed (sequential addition at nu = 0.35, then growth + FIRE),"
  echo "then the sweeps of Monte Carlo with swaps (figure 11 since 2026-11-29: event chains and swaps;"
  echo "figure 12: Metropolis moves and swaps; experiments/*.toml); - where the result predates those columns."
  echo "Rendered by plots/model_errors.sh from the result CSVs."
  echo
  table "results/fig11$suffix.csv" "Figure 11 (T/N against nu)"
  if [ -f "results/fig11_placed$suffix.csv" ]; then
    table "results/fig11_placed$suffix.csv" \
      "Figure 11, packings as placed by sequential addition (\`hgrid run experiments/fig11_placed.toml --scale $scale\`, not part of make figures)"
  fi
  if [ -f "results/fig11_equilibrated$suffix.csv" ]; then
    if [ "$scale" = paper ]; then what="omega = 10, nu = 0.6, N = 10^6, packing equilibrated (3000 sweeps"
    else what="nu = 0.6, N = 10^5, packings equilibrated (10^4 sweeps"; fi
    table "results/fig11_equilibrated$suffix.csv" \
      "Figure 11, $what of Monte Carlo with swaps; \`hgrid run experiments/fig11_equilibrated.toml --scale $scale\`, not part of make figures)"
  fi
  if [ -f "results/fig11_growth_equilibrated$suffix.csv" ]; then
    table "results/fig11_growth_equilibrated$suffix.csv" \
      "Figure 11, nu = 0.6, N = 10^5, packings by compression, then equilibrated (10^4 sweeps of Monte Carlo with swaps; \`hgrid run experiments/fig11_growth_equilibrated.toml --jobs 2\`, not part of make figures)"
  fi
  table "results/fig12$suffix.csv" "Figure 12 (T/N against N)"
  if [ -f "results/fig12_placed$suffix.csv" ]; then
    table "results/fig12_placed$suffix.csv" \
      "Figure 12, packings as placed by sequential addition (\`hgrid run experiments/fig12_placed.toml --scale $scale\`, not part of make figures)"
  fi
  if [ -f "results/fig12_equilibrated$suffix.csv" ]; then
    table "results/fig12_equilibrated$suffix.csv" \
      "Figure 12, N <= 3·10^4, packings equilibrated (10^4 sweeps of Monte Carlo with swaps; \`hgrid run experiments/fig12_equilibrated.toml\`, not part of make figures)"
  fi
  if [ -f "results/fig12_growth$suffix.csv" ]; then
    table "results/fig12_growth$suffix.csv" \
      "Figure 12, packings by compression (sequential addition at nu = 0.35, then growth + FIRE; \`hgrid run experiments/fig12_growth.toml --scale $scale\`, not part of make figures)"
  fi
  if [ -f "results/fig12_growth_equilibrated$suffix.csv" ]; then
    if [ "$scale" = paper ]; then what="N = 10^5"; else what="N <= 3·10^4"; fi
    table "results/fig12_growth_equilibrated$suffix.csv" \
      "Figure 12, $what, packings by compression, then equilibrated (10^4 sweeps of Monte Carlo with swaps; \`hgrid run experiments/fig12_growth_equilibrated.toml --jobs 2 --scale $scale\`, not part of make figures)"
  fi
  if [ -f "results/fig12_large_equilibrated$suffix.csv" ]; then
    if [ "$scale" = paper ]; then what="N = 10^6, 3000 sweeps"; else what="N = 3·10^5, 10^4 sweeps"; fi
    table "results/fig12_large_equilibrated$suffix.csv" \
      "Figure 12, alpha = -3, $what of Monte Carlo with swaps after compression (\`hgrid run experiments/fig12_large_equilibrated.toml --scale $scale\`, not part of make figures)"
  fi
} > "$tmp"
mv -f "$tmp" "$out"
echo "wrote $out" >&2
