#!/usr/bin/env bash
# Builds MercuryDPM's kernel from a source checkout and hgridlab's drivers
# against it, outside hgridlab's own build. Nothing is downloaded.
#   MERCURYDPM_SRC=/path/to/MercuryDPM bash bench/mercurydpm/build.sh
# MERCURYDPM_BUILD (default build-mercurydpm/) receives mercurydpm/ (the
# kernel), drivers/ (mercurydpm_free_cooling, mercurydpm_write_restart, mercurydpm_peer, mercurydpm_pour) and COMMIT (the commit built:
# `git rev-parse HEAD` of the checkout, or its COMMIT file for a git archive).
# Without MERCURYDPM_SRC it says so and exits 0 (the comparison is optional).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
src=${MERCURYDPM_SRC:-}
if [ -z "$src" ]; then
  echo "MercuryDPM comparison skipped: MERCURYDPM_SRC is not set (a MercuryDPM source tree; see docs/MERCURYDPM.md)"
  exit 0
fi
[ -f "$src/Kernel/Mercury2D.h" ] || { echo "MERCURYDPM_SRC=$src: no Kernel/Mercury2D.h (not a MercuryDPM source tree)" >&2; exit 2; }
out=${MERCURYDPM_BUILD:-build-mercurydpm}
mkdir -p "$out"
out=$(cd "$out" && pwd)
jobs=${JOBS:-$(nproc)}
commit=$(git -C "$src" rev-parse HEAD 2>/dev/null || cat "$src/COMMIT" 2>/dev/null || echo unknown)
cmake -S "$src" -B "$out/mercurydpm" -DMercuryDPM_KERNEL_ONLY=ON -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$out/mercurydpm" -j "$jobs" --target MercuryBase
cmake -S "$here" -B "$out/drivers" -DCMAKE_BUILD_TYPE=Release -DMERCURYDPM_SRC="$src" \
  -DMERCURYDPM_BUILD="$out/mercurydpm" >/dev/null
cmake --build "$out/drivers" -j "$jobs"
echo "$commit" > "$out/COMMIT"
echo "MercuryDPM $commit built: $out/drivers/mercurydpm_free_cooling"
