#!/usr/bin/env bash
# Benchmark (b) of the contact list (docs/CONTACT_LIST.md, the performance
# record): LAMMPS pours 20 000 spheres (in.pour_bench) three times, one MPI
# task, `newton off`: with `neighbor 0.2 bin` (writing the two windows'
# dumps), with `neighbor 0.2 multi` and the collections `hgrid recommend`
# gives for the bed (one), and with two collections (diameters <= 0.5,
# <= 1.0). Its neighbour time per build in each window (the window run's
# Neigh seconds / its neighbour list builds) is printed beside pour_replay's
# (build/pour_replay) replay of the same window: the grid rebuilt every
# frame, the contact list at a scan of skins and the model's, and the list's
# build at skin 0.2. About 20 minutes on one core; the dumps take ~0.8 GB.
# Resumable: a LAMMPS run whose log in WORK_DIR is complete is not rerun.
#   experiments/beds/pour_bench.sh [BUILD_DIR] [WORK_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../build}" && pwd)
work=${2:-$(mktemp -d)}
mkdir -p "$work"
command -v lmp >/dev/null || { echo "pour_bench.sh: lmp (LAMMPS) not found; apt-get install lammps" >&2; exit 2; }
[ -x "$build/pour_replay" ] || { echo "pour_bench.sh: $build/pour_replay not built (make pour_replay)" >&2; exit 2; }
cd "$work"
run() {  # name, then lmp -var arguments; a run whose log is complete is not run again
  local name=$1; shift
  if [ -f "log.$name" ] && grep -q "^Total wall time" "log.$name" && { [ "$name" != bin ] || [ -f pour.B.dump ]; }; then
    echo "pour_bench.sh: LAMMPS run '$name' done before ($work/log.$name)" >&2
    return
  fi
  echo "pour_bench.sh: LAMMPS run '$name' ($work/log.$name), a few minutes" >&2
  lmp -in "$here/in.pour_bench" "$@" -log "log.$name.tmp" -screen none
  mv "log.$name.tmp" "log.$name"
}
# Neigh seconds / builds of the run after each WINDOW line of a log.
per_build() {
  awk -v name="$1" '
    /^WINDOW/ { w = $2; next }
    w != "" && /^Neigh / { neigh = $5 }
    w != "" && /^Neighbor list builds =/ {
      printf "LAMMPS %-7s window %s: %.3e s per build (Neigh %.3f s, %d builds)\n", name, w, $5 ? neigh / $5 : 0, neigh, $5
      w = ""
    }
  ' "log.$1"
}
run bin -var neigh bin -var out pour
run multi1 -var neigh multi -var collections "collection/interval 1 1"
run multi2 -var neigh multi -var collections "collection/interval 2 0.5 1"
echo "# $(date -u +%F), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //') ($(nproc) cores), LAMMPS$(lmp -h | grep -m1 -o ' - [0-9].*$' | sed 's/^ -//'), $("$build/hgrid" --version | head -n 1)"
for name in bin multi1 multi2; do per_build $name; done
for w in A B; do
  echo "pour_bench.sh: replaying window $w" >&2
  "$build/pour_replay" "pour.$w.dump" --rounds 3
done
