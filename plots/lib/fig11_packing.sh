# Sourced by the scripts that draw one figure-11 packing (alpha = -3,
# omega = 100, nu = 0.6, excluded volume as experiments/fig11.toml makes it,
# seed 1) at a scale: sets scale,
# hgrid, n, suffix and packing (generated into, or taken from, the cache),
# and defines draw NAME GP CSV [GNUPLOT_VARS]: paper_figs/NAME$suffix.png and
# .pdf, each under a temporary name first. Scales: default N = 10^5, paper
# 10^6, smoke 3*10^4 (the smallest box that holds 4 r_max).
scale=${1:-default}
hgrid=${HGRID:-build/hgrid}
case "$scale" in smoke) n=30000 ;; paper) n=1000000 ;; *) n=100000 ;; esac
suffix=$([ "$scale" = default ] && echo "" || echo "-$scale")
mkdir -p results paper_figs results/packings
source plots/lib/fig11_protocol.sh "$scale"
# shellcheck disable=SC2046  # excluded_args: several options
packing=$("$hgrid" generate --n "$n" --nu 0.6 --omega 100 --alpha -3 --placement excluded $(excluded_args 100) --seed 1 \
          --cache results/packings --quiet | tail -1)

draw() {
  local name=$1 gp=$2 csv=$3 vars=${4:-} fmt
  for fmt in png pdf; do
    local out="paper_figs/$name$suffix.$fmt" t="paper_figs/.$name$suffix.tmp.$fmt"
    gnuplot -e "in='$csv'; out='$t'; fmt='$fmt'; n='$n'; $vars" "$gp"
    if [ "$fmt" = pdf ]; then plots/lib/pdf_fixdate.sh "$t"; fi
    mv -f "$t" "$out"
  done
  echo "wrote $csv and paper_figs/$name$suffix.png|pdf" >&2
}
