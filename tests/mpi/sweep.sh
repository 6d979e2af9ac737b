#!/usr/bin/env bash
# Scene sweeps under mpirun: `hgrid run` on 1 to 4 ranks writes the counts a
# run without MPI writes; a run that failed on one rank (one packing of the
# scene cannot be written) fails every rank, names the point and writes no
# result file; a rerun on another number of ranks reuses the points the
# failed run measured. Usage: sweep.sh HGRID MPIEXEC WORKDIR
set -euo pipefail
hgrid=$(realpath "$1") mpiexec=$2 work=$3
src=$(cd "$(dirname "$0")/../.." && pwd)
scene=$src/experiments/regression.toml
rm -rf "$work"
mkdir -p "$work"
cd "$work"

fail() { echo "sweep.sh: FAILED: $*" >&2; exit 1; }
ranks() { local np=$1; shift; "$mpiexec" --oversubscribe -np "$np" "$hgrid" "$@"; }
# The CSV without its comment line and its timing columns (seconds_*).
counts() {
  awk -F, '/^#/ { next }
    !cols { for (i = 1; i <= NF; ++i) if ($i !~ /^seconds_/) keep[++cols] = i }
    { line = $keep[1]; for (k = 2; k <= cols; ++k) line = line "," $keep[k]; print line }' "$1"
}
# Runs a command, printing how long it took; its exit status.
timed() {
  local label=$1 t0 t1 status=0; shift
  t0=$(date +%s.%N)
  "$@" || status=$?
  t1=$(date +%s.%N)
  awk -v l="$label" -v a="$t0" -v b="$t1" 'BEGIN { printf "sweep.sh: %s: %.1f s\n", l, b - a }'
  return "$status"
}

# Serial, then 1 to 4 ranks, each with its own packing cache (so the ranks
# generate the packings too).
timed "serial" "$hgrid" run "$scene" --results serial --packings serial/packings 2>serial.err \
  || { cat serial.err; fail "serial run"; }
counts serial/regression.csv >serial.counts
[ "$(wc -l <serial.counts)" -eq 33 ] || fail "serial CSV: expected a header and 32 rows"
for np in 1 2 3 4; do
  timed "$np rank(s)" ranks "$np" run "$scene" --results np$np --packings np$np/packings 2>np$np.err \
    || { cat np$np.err; fail "run on $np rank(s)"; }
  counts np$np/regression.csv | cmp -s - serial.counts || fail "$np rank(s): counts differ from the serial run"
  [ -e np$np/regression.h5 ] || fail "$np rank(s): no regression.h5"
  ls np$np/regression.journal* >/dev/null 2>&1 && fail "$np rank(s): journal left behind"
  [ "$(grep -c '^hgrid run: wrote' np$np.err)" -eq 1 ] || fail "$np rank(s): 'wrote' not said once"
done

# Failure on one rank: one packing's cache file is a directory, so writing
# that packing fails on the rank that owns its two points, and only there.
# The serial run made the packings in group order (oldest first); on 2 ranks
# of equal groups, the second group (points 3 and 4) is rank 1's.
mkdir -p fail/packings
blocked=$(cd serial/packings && ls -tr -- *.h5 | sed -n 2p)
mkdir fail/packings/"$blocked"
status=0
ranks 2 run "$scene" --results fail --packings fail/packings 2>fail.err || status=$?
[ "$status" -eq 2 ] || { cat fail.err; fail "failed run: exit status $status, expected 2"; }
grep -q "^hgrid: error: rank 1: out: .*$blocked.*\[at point 3 of 32 (d=3 n=20000 nu=0.6 alpha=0 omega=10 " fail.err \
  || { cat fail.err; fail "failed run: the error does not name rank 1's point"; }
[ -e fail/regression.h5 ] || [ -e fail/regression.csv ] && fail "failed run: result files written"
ls fail/regression.journal*.jsonl >/dev/null 2>&1 || fail "failed run: the measured points were not journaled"
echo "sweep.sh: the failed run said: $(grep '^hgrid: error' fail.err)"

# Resume on 3 ranks: the points measured before the failure are reused.
rmdir fail/packings/"$blocked"
timed "resume on 3 ranks" ranks 3 run "$scene" --results fail --packings fail/packings 2>resume.err \
  || { cat resume.err; fail "resumed run"; }
grep -q "points reused from" resume.err || { cat resume.err; fail "resumed run: nothing reused"; }
counts fail/regression.csv | cmp -s - serial.counts || fail "resumed run: counts differ from the serial run"
ls fail/regression.journal* >/dev/null 2>&1 && fail "resumed run: journal left behind"

# A DPM scene is one simulation: refused on more than one rank, naming `kind`.
status=0
ranks 2 run "$src/experiments/dpm_free_cooling.toml" --results dpm 2>dpm.err || status=$?
[ "$status" -eq 2 ] && grep -q "^hgrid: error: kind: " dpm.err || { cat dpm.err; fail "DPM scene on 2 ranks"; }
echo "sweep.sh: OK"
