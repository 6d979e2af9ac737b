#!/usr/bin/env bash
# Runs every fuzz target for SECONDS seconds (default 60) from its seed corpus
# (tests/fuzz/corpus/<target>/), after replaying the inputs that once crashed
# it (tests/fuzz/crashes/<target>-*). A crash, a leak or a timeout fails the
# run; its input is left in build-fuzz/ and should be kept under
# tests/fuzz/crashes/ once fixed. Usage: tests/fuzz/run.sh BUILD_DIR [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build-fuzz}
seconds=${2:-60}
for target in csv particles scene journal hdf5; do
  bin="$build/fuzz_$target"
  work="$build/fuzz-corpus/$target"  # the growing corpus stays out of the repository
  mkdir -p "$work"
  shopt -s nullglob
  crashes=(tests/fuzz/crashes/"$target"-*)
  shopt -u nullglob
  if [ ${#crashes[@]} -gt 0 ]; then
    echo "== fuzz_$target: replaying ${#crashes[@]} kept crash input(s)"
    "$bin" "${crashes[@]}" > "$build/fuzz_$target-replay.log" 2>&1 || {
      echo "fuzz_$target FAILED on a kept crash input; the log: $build/fuzz_$target-replay.log" >&2
      exit 1
    }
  fi
  echo "== fuzz_$target: $seconds s"
  # -timeout: an input taking longer is a hang (the HDF5 child has 5 s of its own).
  log="$build/fuzz_$target.log"
  rc=0
  (cd "$build" && "./fuzz_$target" -max_total_time="$seconds" -timeout=25 -rss_limit_mb=4096 \
      -artifact_prefix="fuzz_$target-" -print_final_stats=1 "fuzz-corpus/$target" "$OLDPWD/tests/fuzz/corpus/$target") \
    > "$log" 2>&1 || rc=$?
  grep -E "^(stat::number_of_executed_units|Test unit written)" "$log" || true
  if [ "$rc" -ne 0 ]; then
    echo "fuzz_$target FAILED (exit $rc); the log: $log" >&2
    tail -n 40 "$log" >&2
    exit 1
  fi
done
echo "fuzz: every target ran clean"
