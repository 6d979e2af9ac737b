#!/usr/bin/env bash
# The ghost layer of the decomposed search (hgrid count --decompose under
# mpirun) against one 2 r_max shell, as a function of omega: 3D periodic
# boxes of random centres, alpha = -3, nu = 0.6, the recommended Top-Down
# sizes, on 2 and 4 ranks (cached packings under results/packings/).
# Writes results/ghosts[-SCALE].csv and paper_figs/ghosts[-SCALE].png|pdf.
# Skipped with a message when mpirun or an MPI build of hgrid is missing.
# Usage: plots/ghosts.sh [SCALE]   (default N = 10^5, paper 10^6, smoke 2*10^4)
set -euo pipefail
cd "$(dirname "$0")/.."
scale=${1:-default}
hgrid=${HGRID:-build/hgrid}
mpirun=${MPIRUN:-mpirun}
case "$scale" in smoke) n=20000; omegas="1 10 100 1000" ;;
                 paper) n=1000000; omegas="1 2 5 10 20 50 100 200 500 1000" ;;
                 *) n=100000; omegas="1 2 5 10 20 50 100 200 500 1000" ;; esac
suffix=$([ "$scale" = default ] && echo "" || echo "-$scale")
for tool in "$mpirun" jq; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "plots/ghosts.sh: $tool is not installed (optional); ghost figure skipped" >&2
    exit 0
  fi
done
# Root may run mpirun only when it says so; more ranks than cores are fine here.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
mkdir -p results results/packings paper_figs
csv=results/ghosts$suffix.csv
tmp=$csv.tmp.$$
trap 'rm -f "$tmp"' EXIT
{
  echo "# ghosts of the decomposed search (mpirun -np P hgrid count --decompose): alpha=-3 d=3 periodic random centres nu=0.6 n=$n seed=1, recommended Top-Down sizes"
  echo "# ghosts: copies received by all ranks (level-aware: a particle of radius r goes to bricks within 2r); shell_ghosts: with one 2 r_max shell for every particle"
  echo "# halo_volume: a brick's halo grown by 2r averaged over the particles; halo_volume_shell: grown by 2 r_max (box volume units)"
  echo "# git_hash=$(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)"
  echo "omega,ranks,n,bricks,ghosts,shell_ghosts,shell_over_level_aware,halo_volume,halo_volume_shell,T_over_N,model_T_over_N"
  for omega in $omegas; do
    f=$("$hgrid" generate --d 3 --n "$n" --nu 0.6 --alpha -3 --omega "$omega" --placement random \
          --seed 1 --cache results/packings --quiet | tail -1)
    sizes=$("$hgrid" recommend "$f" --json | jq -r '.sizes | map(tostring) | join(",")')
    for ranks in 2 4; do
      "$mpirun" -np "$ranks" "$hgrid" count "$f" --sizes "$sizes" --decompose --threads 1 --json </dev/null |
        jq -r --arg w "$omega" '
          (.box | .[0] * .[1] * .[2]) as $v |
          [$w, .ranks, .n, (.bricks | map(tostring) | join("x")), .ghosts, .shell_ghosts,
           .shell_over_level_aware, .halo_volume / $v, .halo_volume_shell / $v, .T_over_N, .model_T_over_N] | @csv' |
        tr -d '"'
    done
    echo "plots/ghosts.sh: omega = $omega done" >&2
  done
} > "$tmp"
if [ "$(grep -vc '^#' "$tmp")" -le 1 ] || ! awk -F, '!/^#/ && NR > 5 && $2 == 1 {exit 1}' "$tmp"; then
  echo "plots/ghosts.sh: hgrid ran as one rank under mpirun (built without MPI?); ghost figure skipped" >&2
  exit 0
fi
mv "$tmp" "$csv"
for fmt in png pdf; do
  out="paper_figs/ghosts$suffix.$fmt" t="paper_figs/.ghosts$suffix.tmp.$fmt"
  gnuplot -e "in='$csv'; out='$t'; fmt='$fmt'; n='$n'" plots/ghosts.gp
  if [ "$fmt" = pdf ]; then plots/lib/pdf_fixdate.sh "$t"; fi
  mv -f "$t" "$out"
done
echo "plots/ghosts.sh: wrote $csv and paper_figs/ghosts$suffix.png|pdf" >&2
awk -F, '/^#/ || !h++ {next} $1 == 100 {printf "ghosts: omega = 100 on %d ranks: %.1f x fewer than a 2 r_max shell\n", $2, $7}' "$csv" >&2
