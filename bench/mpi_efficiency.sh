#!/usr/bin/env bash
# Parallel efficiency of the decomposed count (docs/record/PERFORMANCE.md, MPI):
# the serial count (1 thread) and `mpirun -np P ... --decompose` (1 thread
# per rank) alternated R times on one packing, with the sizes `hgrid
# recommend` gives for it. Prints each run's seconds, then per round and for
# the fastest runs: serial (build + query) / (P x (exchange + build + query)),
# each phase the slowest rank's. Run nothing else meanwhile.
#
#   bash bench/mpi_efficiency.sh FILE.h5 [P=2] [R=3]      (HGRID=path/to/hgrid)
set -euo pipefail
if [ $# -lt 1 ]; then
  echo "usage: bash bench/mpi_efficiency.sh FILE.h5 [ranks=2] [rounds=3]" >&2
  exit 2
fi
file=$1; P=${2:-2}; R=${3:-3}
hgrid=${HGRID:-build/hgrid}
command -v jq > /dev/null || { echo "mpi_efficiency.sh: needs jq (apt-get install jq)" >&2; exit 2; }
command -v mpirun > /dev/null || { echo "mpi_efficiency.sh: needs mpirun (apt-get install openmpi-bin)" >&2; exit 2; }
[ "$(id -u)" = 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
sizes=$("$hgrid" recommend "$file" --json | jq -r '.sizes | map(tostring) | join(",")')
echo "sizes $sizes, $P ranks, $R rounds" >&2
best_s=inf; best_m=inf
for r in $(seq "$R"); do
  s=$("$hgrid" count "$file" --sizes "$sizes" --threads 1 --json | jq '.seconds_build + .seconds_query')
  m=$(mpirun -np "$P" "$hgrid" count "$file" --sizes "$sizes" --decompose --threads 1 --json < /dev/null |
      jq -r '"\(.seconds_exchange + .seconds_build + .seconds_query) \(.seconds_exchange) \(.seconds_build) \(.seconds_query)"')
  read -r total x b q <<< "$m"
  awk -v r="$r" -v s="$s" -v t="$total" -v x="$x" -v b="$b" -v q="$q" -v P="$P" 'BEGIN {
    printf "round %d: serial %.3f s; %d ranks %.3f s (exchange %.3f, build %.3f, query %.3f); efficiency %.1f %%\n",
           r, s, P, t, x, b, q, 100 * s / (P * t) }'
  best_s=$(awk -v a="$best_s" -v b="$s" 'BEGIN { print (a == "inf" || b < a) ? b : a }')
  best_m=$(awk -v a="$best_m" -v b="$total" 'BEGIN { print (a == "inf" || b < a) ? b : a }')
done
awk -v s="$best_s" -v t="$best_m" -v P="$P" 'BEGIN {
  printf "fastest: serial %.3f s, %d ranks %.3f s: efficiency %.1f %%\n", s, P, t, 100 * s / (P * t) }'
