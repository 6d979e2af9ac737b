# Sourced by the scripts that measure structure in excluded-volume packings
# with numpy (plots/wall_edges.sh, plots/wall_pairs.sh). Expects `csv` (the
# results file) and the script's name in `script`; sets hgrid, py, tmp and
# work (both removed on exit) and defines stamp (the CSV's provenance line)
# and xyz BOUNDARY N SWEEPS OUT: the 3D packing alpha = -3, omega = 10,
# nu = 0.6, seed 1 (after SWEEPS Monte Carlo sweeps; generated into, or taken
# from, results/packings) as XYZ in OUT, printing the packing file. Exits 0
# with a message when numpy is missing.
hgrid=${HGRID:-build/hgrid}
py=${PYTHON:-python3}
if ! "$py" -c 'import numpy' >/dev/null 2>&1; then
  echo "$script: $py has no numpy (apt-get install python3-numpy, or PYTHON=/usr/bin/python3); skipped" >&2
  exit 0
fi
mkdir -p results results/packings
tmp=$csv.tmp.$$
work=$(mktemp -d)
trap 'rm -rf "$tmp" "$work"' EXIT

xyz() {
  local boundary=$1 n=$2 sweeps=$3 out=$4 file eq=()
  [ "$sweeps" -gt 0 ] && eq=(--equilibrate --sweeps "$sweeps")
  file=$("$hgrid" generate --d 3 --n "$n" --nu 0.6 --alpha -3 --omega 10 --placement excluded --boundary "$boundary" \
    --seed 1 "${eq[@]}" --quiet --cache results/packings | tail -n 1 | awk '{print $NF}')
  "$hgrid" export "$file" --xyz "$out" >/dev/null
  echo "$file"
}

# The provenance comment line of the CSV: commit and machine.
stamp() {
  echo "# git_hash=$(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown) machine=$(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | cut -d: -f2 | sed 's/^ //' || echo unknown)"
}
