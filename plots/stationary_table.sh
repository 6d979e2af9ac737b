#!/usr/bin/env bash
# The packings that stop when stationary against a reference run of fixed
# sweeps: a markdown table of every excluded-volume point of two result CSVs
# of one scene (matched on boundary, alpha, omega, nu, n, seed): the sweeps
# each took, T/N in both, their difference, and the excluded-volume model's
# error of the new one. Usage:
#   plots/stationary_table.sh REFERENCE.csv NEW.csv
# e.g. git show 8a9e089:results/fig11.csv > /tmp/fig11-1000.csv &&
#      plots/stationary_table.sh /tmp/fig11-1000.csv results/fig11.csv
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 REFERENCE.csv NEW.csv" >&2; exit 2; }
awk -F, '
  FNR == 1 { file++ }
  /^#/ { next }
  !seen[file]++ { for (i = 1; i <= NF; i++) col[file, $i] = i; next }
  function v(name) { return $(col[file, name]) }
  v("placement") != "excluded" { next }
  {
    key = v("boundary") SUBSEP v("alpha") + 0 SUBSEP v("omega") + 0 SUBSEP sprintf("%.3f", v("nu")) SUBSEP v("n") + 0 SUBSEP v("seed") + 0
    if (file == 1) { ref[key] = v("T_over_N"); ref_sweeps[key] = v("equilibration_sweeps"); next }
    keys[++k] = key; t[key] = v("T_over_N"); sw[key] = v("equilibration_sweeps"); ex[key] = v("model_excluded_T_over_N")
  }
  END {
    print "| boundary | alpha | omega | nu | N | sweeps (reference) | T/N reference | T/N stationary | difference | excluded-volume model error |"
    print "|---|---|---|---|---|---|---|---|---|---|"
    worst = 0
    for (i = 1; i <= k; i++) {
      key = keys[i]; split(key, f, SUBSEP)
      if (!(key in ref)) { printf "| %s | %s | %s | %s | %s | %d | - | %.4f | - | %+.2f %% |\n", f[1], f[2], f[3], f[4], f[5], sw[key], t[key], 100 * (t[key] / ex[key] - 1); continue }
      d = 100 * (t[key] / ref[key] - 1)
      if (d < 0 ? -d > worst : d > worst) worst = d < 0 ? -d : d
      printf "| %s | %s | %s | %s | %s | %d (%d) | %.4f | %.4f | %+.2f %% | %+.2f %% |\n", f[1], f[2], f[3], f[4], f[5], sw[key], ref_sweeps[key], ref[key], t[key], d, 100 * (t[key] / ex[key] - 1)
    }
    printf "\nlargest |difference|: %.2f %%\n", worst
  }' "$1" "$2"
