#!/usr/bin/env bash
# Runs every fuzz target for SECONDS seconds (default 60) from its seed corpus
# (tests/fuzz/corpus/<target>/), after replaying the inputs that once crashed
# it (tests/fuzz/crashes/<target>-*). A crash, a leak or a timeout fails the
# run; its input is left in build-fuzz/ and should be kept under
# tests/fuzz/crashes/ once fixed. The targets run side by side, one per core
# (FUZZ_JOBS to change it). Usage: tests/fuzz/run.sh BUILD_DIR [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build-fuzz}
seconds=${2:-60}
jobs=${FUZZ_JOBS:-$(nproc 2>/dev/null || echo 1)}  # targets run side by side, one core each
case "$jobs" in
  '' | *[!0-9]* | 0) echo "tests/fuzz/run.sh: FUZZ_JOBS must be a whole number >= 1 (got '$jobs')" >&2; exit 2 ;;
esac

# One target: its kept crash inputs, then SECONDS of fuzzing; what it says
# goes to $build/fuzz_$target.out (printed in order at the end).
fuzz_one() {
  # work: the growing corpus, kept out of the repository
  local target=$1 bin="$build/fuzz_$1" work="$build/fuzz-corpus/$1" log="$build/fuzz_$1.log" rc=0
  mkdir -p "$work"
  shopt -s nullglob
  local crashes=(tests/fuzz/crashes/"$target"-*)
  shopt -u nullglob
  if [ ${#crashes[@]} -gt 0 ]; then
    echo "== fuzz_$target: replaying ${#crashes[@]} kept crash input(s)"
    "$bin" "${crashes[@]}" > "$build/fuzz_$target-replay.log" 2>&1 || {
      echo "fuzz_$target FAILED on a kept crash input; the log: $build/fuzz_$target-replay.log"
      return 1
    }
  fi
  echo "== fuzz_$target: $seconds s"
  # -timeout: an input taking longer is a hang (the HDF5 child has 5 s of its own).
  (cd "$build" && "./fuzz_$target" -max_total_time="$seconds" -timeout=25 -rss_limit_mb=4096 \
      -artifact_prefix="fuzz_$target-" -print_final_stats=1 "fuzz-corpus/$target" "$OLDPWD/tests/fuzz/corpus/$target") \
    > "$log" 2>&1 || rc=$?
  grep -E "^(stat::number_of_executed_units|Test unit written)" "$log" || true
  if [ "$rc" -ne 0 ]; then
    echo "fuzz_$target FAILED (exit $rc); the log: $log"
    tail -n 40 "$log"
    return 1
  fi
}

mkdir -p "$build"  # each target's lines go to a file there
targets=(csv particles scene journal hdf5)
# Lane k runs targets k, k + jobs, ... one after another; the lanes side by side.
lanes=()
for ((k = 0; k < jobs && k < ${#targets[@]}; k++)); do
  (
    lane_rc=0
    for ((i = k; i < ${#targets[@]}; i += jobs)); do
      fuzz_one "${targets[$i]}" > "$build/fuzz_${targets[$i]}.out" 2>&1 || lane_rc=1
    done
    exit "$lane_rc"
  ) &
  lanes+=($!)
done
failed=0
for pid in "${lanes[@]}"; do wait "$pid" || failed=1; done
for target in "${targets[@]}"; do cat "$build/fuzz_$target.out"; done
if [ "$failed" -ne 0 ]; then
  echo "fuzz: a target FAILED (above)" >&2
  exit 1
fi
echo "fuzz: every target ran clean"
