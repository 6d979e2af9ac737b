#!/usr/bin/env bash
# Compact tables of measured T/N over predicted T/N (paper's model / hgridlab's
# excluded-volume model) for Figs. 11 and 12, as printed in
# paper_figs/README.md. Fig. 11: one row per omega at the scene's largest N,
# random centres and excluded volume at the smallest and largest nu. Fig. 12:
# one row per alpha, one column per boundary and N (the smallest N and the
# powers of ten). Reads results/fig11[-S].csv
# and fig12[-S].csv; writes Markdown to stdout.
# Usage: plots/ratio_tables.sh [SCALE]
set -euo pipefail
cd "$(dirname "$0")/.."
scale=${1:-default}
suffix=$([ "$scale" = default ] && echo "" || echo "-$scale")

# Fig. 11: random centres have only the paper's model (their excluded-volume column is NaN).
awk -F, '
  /^#/ { if (!hdr) prov = $0; next }
  !hdr { for (i = 1; i <= NF; i++) c[$i] = i; hdr = 1; next }
  { n = $c["n"] + 0; if (n > nmax) nmax = n
    nu = $c["nu"] + 0; if (numin == "" || nu < numin) numin = nu; if (nu > numax) numax = nu
    k = $c["omega"] + 0 SUBSEP $c["placement"] SUBSEP nu SUBSEP n
    p[k] = $c["T_over_N"] / $c["model_T_over_N"]
    if ($c["placement"] == "excluded") e[k] = $c["T_over_N"] / $c["model_excluded_T_over_N"]
    if (!((($c["omega"] + 0)) in seen)) { seen[$c["omega"] + 0] = 1; om[++no] = $c["omega"] + 0 } }
  END {
    printf "Fig. 11 at N = %d, measured T/N over predicted (paper model / excluded-volume model):\n\n", nmax
    printf "| omega | random, nu = %g | random, nu = %g | excluded, nu = %g | excluded, nu = %g |\n|---|---|---|---|---|\n", numin, numax, numin, numax
    for (i = 1; i <= no; i++) {
      w = om[i]; printf "| %g", w
      split("random random excluded excluded", pl, " "); split(numin " " numax " " numin " " numax, nv, " ")
      for (j = 1; j <= 4; j++) {
        k = w SUBSEP pl[j] SUBSEP nv[j] + 0 SUBSEP nmax
        if (!(k in p)) printf " | -"
        else if (pl[j] == "random") printf " | %.3f", p[k]
        else printf " | %.3f / %.3f", p[k], e[k]
      }
      print " |"
    }
    print "\nSource: " prov "\n"
  }' "results/fig11$suffix.csv"

awk -F, '
  /^#/ { if (!hdr) prov = $0; next }
  !hdr { for (i = 1; i <= NF; i++) c[$i] = i; hdr = 1; next }
  { a = $c["alpha"] + 0; b = $c["boundary"]; n = $c["n"] + 0
    k = a SUBSEP b SUBSEP n
    r[k] = sprintf("%.3f / %.3f", $c["T_over_N"] / $c["model_T_over_N"], $c["T_over_N"] / $c["model_excluded_T_over_N"])
    if (!(a in sa)) { sa[a] = 1; al[++na] = a }
    if (nmin == "" || n < nmin) nmin = n
    if (!((b SUBSEP n) in sc)) { sc[b SUBSEP n] = 1; cb[++nc] = b; cn[nc] = n } }
  END {
    m = 0; for (i = 1; i <= nc; i++) { l = log(cn[i]) / log(10)  # keep the smallest N and the powers of ten
      if (cn[i] == nmin || (l - int(l + 0.5))^2 < 1e-18) { m++; cb[m] = cb[i]; cn[m] = cn[i] } }
    nc = m
    # columns: walls first, then periodic, each by ascending N; rows by descending alpha
    for (i = 1; i <= nc; i++) for (j = i + 1; j <= nc; j++)
      if (cb[j] > cb[i] || (cb[j] == cb[i] && cn[j] < cn[i])) { t = cb[i]; cb[i] = cb[j]; cb[j] = t; t = cn[i]; cn[i] = cn[j]; cn[j] = t }
    for (i = 1; i <= na; i++) for (j = i + 1; j <= na; j++) if (al[j] > al[i]) { t = al[i]; al[i] = al[j]; al[j] = t }
    print "Fig. 12, measured T/N over predicted (paper model / excluded-volume model):\n"
    printf "| alpha"; for (i = 1; i <= nc; i++) printf " | %s %d", cb[i], cn[i]; print " |"
    printf "|---"; for (i = 1; i <= nc; i++) printf "|---"; print "|"
    for (j = 1; j <= na; j++) {
      printf "| %g", al[j]
      for (i = 1; i <= nc; i++) { k = al[j] SUBSEP cb[i] SUBSEP cn[i]; printf " | %s", (k in r) ? r[k] : "-" }
      print " |"
    }
    print "\nSource: " prov
  }' "results/fig12$suffix.csv"
