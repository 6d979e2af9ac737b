#!/usr/bin/env bash
# The include order of the stages: a file below src/<stage>/ includes only
# from its own stage and the stages before it (base, grid, domain, contacts,
# model, packing, io, measure, dpm, calibration, advice, scenes, mpi); another stage's
# detail/ is never included; examples/ include installed public headers
# only. Usage: check_includes.sh SRC_ROOT
set -euo pipefail
root="${1:-.}"
stages=(base grid domain contacts model packing io measure dpm calibration advice scenes mpi)
rank() { local i; for i in "${!stages[@]}"; do [ "${stages[$i]}" = "$1" ] && { echo "$i"; return; }; done; echo -1; }
bad=0
for d in "$root"/src/*/; do  # every folder of src/ is a stage (or the tool)
  d=$(basename "$d")
  [ "$d" = cli ] || [ "$(rank "$d")" -ge 0 ] || { echo "src/$d: a folder in no stage (add it to stages)"; bad=1; }
done
for s in "${stages[@]}"; do
  own=$(rank "$s")
  while IFS= read -r -d '' f; do
    while IFS= read -r inc; do
      case "$inc" in
        hgridlab/*) inc=${inc#hgridlab/} ;;
        */*) [ "$(rank "${inc%%/*}")" -ge 0 ] && { echo "$f: includes \"$inc\": a stage's header is named hgridlab/$inc"; bad=1; }; continue ;;
        *) continue ;;  # a header beside the file
      esac
      target=${inc%%/*}
      r=$(rank "$target")
      if [ "$r" -lt 0 ]; then
        echo "$f: includes \"$inc\", which is in no stage"; bad=1
      elif [ "$r" -gt "$own" ]; then
        echo "$f: includes \"$inc\" of the later stage $target"; bad=1
      elif [ "$target" != "$s" ] && [[ "$inc" == */detail/* ]]; then
        echo "$f: includes \"$inc\", an internal header of stage $target"; bad=1
      fi
    done < <(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$f")
  done < <(find "$root/src/$s" -name '*.[ch]pp' -print0)
done
# The tool and the benchmarks use public headers only; tests, benchmarks and
# the Python module name stage headers hgridlab/STAGE/... too.
while IFS= read -r -d '' f; do
  if grep -qE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"(base|grid|domain|contacts|model|packing|io|measure|dpm|calibration|advice|scenes|mpi)/' "$f"; then
    echo "$f: includes a stage's header without hgridlab/"; bad=1
  fi
done < <(find "$root/tests" "$root/bench" "$root/python" "$root/src/cli" -name '*.[ch]pp' -print0)
while IFS= read -r -d '' f; do
  if grep -E '^[[:space:]]*#[[:space:]]*include[[:space:]]*"(hgridlab/)?[a-z]+/detail/' "$f" | grep -vq '"bench/detail/'; then
    echo "$f: includes a stage's internal header"; bad=1
  fi
done < <(find "$root/src/cli" "$root/bench" -maxdepth 1 -name '*.[ch]pp' -print0)
# The examples are what a user writes: installed public headers only, as
# <hgridlab/...> (no quoted project paths, no detail/).
while IFS= read -r -d '' f; do
  while IFS= read -r inc; do
    case "$inc" in
      \<hgridlab/*/detail/*) echo "$f: includes $inc, an internal header"; bad=1 ;;
      \<hgridlab/*) ;;
      \"*) echo "$f: includes $inc: examples include installed headers, <hgridlab/...>"; bad=1 ;;
    esac
  done < <(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*\([<"][^>"]*[>"]\).*/\1/p' "$f")
done < <(find "$root/examples" -name '*.[ch]pp' -print0)
if [ "$bad" -ne 0 ]; then echo "include order: FAILED"; exit 1; fi
echo "include order: OK (${stages[*]})"
