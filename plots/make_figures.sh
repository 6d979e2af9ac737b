#!/usr/bin/env bash
# `make figures`: the cost-model figures 2-10 of the paper (plus fig13,
# accuracy against time) from data written by `hgrid modelfigs`.
#   1. build/hgrid modelfigs --out results/model   (CSV, "# key=value" headers)
#   2. gnuplot on every plots/figNN-<what>.gp -> paper_figs/figNN-<what>.png|pdf
#      (model figures only; scripts fed by other data are named plots/figNN.gp
#      and run by their own script, e.g. plots/experiments.sh, plots/dpm.sh)
#   3. hook: every executable plots/figures.d/*.sh runs next, with SCALE as $1
#      (e.g. a link to plots/experiments.sh for figures 11-12).
# Fails on any error; every output is written under a temporary name, then renamed.
# Usage: plots/make_figures.sh [SCALE]   (env: HGRID = the hgrid binary)
set -euo pipefail
cd "$(dirname "$0")/.."
scale=${1:-default}
hgrid=${HGRID:-build/hgrid}
data=results/model
mkdir -p "$data" paper_figs

# Fig. 13's time-optimal sizes use the committed calibration's time model
# (one machine's; see results/calibration.json), so the figure is the same
# on every machine.
"$hgrid" modelfigs --out "$data" --time-model results/calibration.json

shopt -s nullglob
for script in plots/fig[0-9][0-9]-*.gp; do
  name=$(basename "$script" .gp)
  for fmt in png pdf; do
    tmp="paper_figs/.$name.tmp.$fmt"
    if [ "$fmt" = png ]; then term="pngcairo enhanced size 1000,700 font 'Helvetica,12'"
    else term="pdfcairo enhanced size 7in,4.9in font 'Helvetica,11'"; fi
    case "$name" in fig04-*|fig05-*|fig07-*|fig08-*|fig10-*)  # two panels side by side
      if [ "$fmt" = png ]; then term="pngcairo enhanced size 1400,600 font 'Helvetica,12'"
      else term="pdfcairo enhanced size 10in,4.3in font 'Helvetica,11'"; fi;;
    esac
    gnuplot -e "datadir='$data'" -e "set terminal $term" -e "set output '$tmp'" "$script"
    if [ "$fmt" = pdf ]; then plots/lib/pdf_fixdate.sh "$tmp"; fi  # a fixed date: same data, same bytes
    mv -f "$tmp" "paper_figs/$name.$fmt"
  done
  echo "wrote paper_figs/$name.png and .pdf" >&2
done

for hook in plots/figures.d/*.sh; do
  [ -x "$hook" ] && "$hook" "$scale"
done
