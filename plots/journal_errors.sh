#!/usr/bin/env bash
# The points a scene run's resume journal holds (a paper-scale run still under
# way) as a markdown table: measured T/N and measured / predicted - 1 for the
# paper's model and the excluded-volume model, as plots/model_errors.sh does
# for finished result files (random centres have no excluded-volume
# prediction: -). Walls first, excluded volume before random
# centres, then alpha from 0 down, omega, nu, N.
# Usage: bash plots/journal_errors.sh results/fig12-paper.journal.jsonl
set -euo pipefail
journal=${1:?usage: bash plots/journal_errors.sh JOURNAL}
command -v jq > /dev/null || { echo "journal_errors.sh: needs jq (apt-get install jq)" >&2; exit 2; }
[[ -r $journal ]] || { echo "journal_errors.sh: cannot read $journal" >&2; exit 2; }
echo "| boundary | placement | alpha | omega | nu | N | measured T/N | paper model | excluded-volume model |"
echo "|---|---|---|---|---|---|---|---|---|"
jq -r '.result | [.boundary, .placement, .alpha, .omega, .nu, .n, .T_over_N,
                  100 * (.T_over_N / .model_T_over_N - 1),
                  (if .model_excluded_T_over_N == null then "-" else 100 * (.T_over_N / .model_excluded_T_over_N - 1) end)] | @tsv' \
  "$journal" | sort -t $'\t' -k1,1r -k2,2 -k3,3gr -k4,4g -k5,5g -k6,6g |
  awk -F '\t' '
    function pct(x) { if (x == "-") return "-"; s = sprintf("%+.1f", x); if (s == "-0.0") s = "+0.0"; return s " %" }
    function abs(x) { return x < 0 ? -x : x }
    { printf "| %s | %s | %g | %g | %g | %d | %.3f | %s | %s |\n", $1, $2, $3, $4, $5, $6, $7, pct($8), pct($9)
      if (abs($8) > paper) paper = abs($8); if ($9 != "-" && abs($9) > excl) excl = abs($9); n++ }
    END { printf "\n%d points; largest |measured/predicted - 1|: paper model %.1f %%, excluded-volume model %.1f %%.\n", n, paper, excl }'
