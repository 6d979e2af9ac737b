#!/usr/bin/env bash
# hgrid pairs|count --decompose under mpirun with 1 to 4 ranks against the
# serial grid (itself tested against brute force): the same pair SET, no
# pair twice, the same contact count; walls and periodic, 2D and 3D, omega
# up to 1000 (one sphere wider than several bricks), bricks thinner than
# r_max. Then bad input: one line on stderr, exit status 2, on every rank.
# Usage: decompose.sh HGRID MPIEXEC WORKDIR
set -euo pipefail
hgrid=$1 mpiexec=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAILED: $*" >&2; exit 1; }
sizes_of() { "$hgrid" recommend "$1" --json 2>/dev/null | python3 -c \
  "import json,sys; print(','.join(repr(x) for x in json.load(sys.stdin)['sizes']))"; }

# Spheres wider than a brick: 3000 of radius 0.045 to 0.135 and four of
# radius 10 to 45 (omega = 1000) in a box of side 100, as CSV (walls and
# periodic); on 3 ranks the bricks are slabs thinner than r_max.
big_spheres() {
  python3 - "$1" "$2" <<'PY'
import random, sys
random.seed(int(sys.argv[2]))
print("# box 100 100 100")
print("# boundary " + sys.argv[1])
print("x,y,z,r")
for r in [0.045 + 0.09 * random.random() for _ in range(3000)] + [45, 30, 20, 10]:
    lo, hi = (0, 100)
    print(",".join("%.17g" % random.uniform(lo, hi) for _ in range(3)) + ",%.17g" % r)
PY
}

cases=0
#        d  n     nu   alpha omega boundary  seed  (n = big: the CSV above)
# (mpirun reads stdin: the cases come through descriptor 3.)
while read -r d n nu alpha omega boundary seed <&3; do
  if [ "$n" = big ]; then
    f=big-${boundary}.csv
    big_spheres "$boundary" "$seed" > "$f"
  else
    f=d${d}-${boundary}-w${omega}-a${alpha}.h5
    "$hgrid" generate --d "$d" --n "$n" --nu "$nu" --alpha "$alpha" --omega "$omega" --boundary "$boundary" \
      --seed "$seed" --out "$f" --quiet 2>/dev/null
  fi
  sizes=$(sizes_of "$f")
  "$hgrid" pairs "$f" --sizes "$sizes" --threads 1 | sort > serial.txt
  expect=$(wc -l < serial.txt)
  for ranks in 1 2 3 4; do
    what="$f (seed $seed) on $ranks ranks"
    "$mpiexec" -np "$ranks" "$hgrid" pairs "$f" --sizes "$sizes" --decompose --threads 1 > got.txt ||
      fail "$what: pairs exited $?"
    sort got.txt > got-sorted.txt
    [ "$(sort -u got.txt | wc -l)" -eq "$(wc -l < got.txt)" ] || fail "$what: a pair reported twice"
    cmp -s serial.txt got-sorted.txt || fail "$what: pair set differs from the serial grid ($(wc -l < got.txt) vs $expect)"
    "$mpiexec" -np "$ranks" "$hgrid" count "$f" --sizes "$sizes" --decompose --threads 1 --json > count.json ||
      fail "$what: count exited $?"
    python3 - "$expect" "$ranks" "$omega" count.json <<'PY' || fail "$what: count"
import json, sys
expect, ranks, omega, path = int(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
j = json.load(open(path))
widths = [side / k for side, k in zip(j["box"], j["bricks"])]
if j["n"] == 3004 and ranks >= 2:  # the largest sphere spans bricks; slabs thinner than it
    assert 2 * j["r_max"] > min(widths) and (ranks != 3 or j["r_max"] > min(widths)), (j["r_max"], widths)
assert j["contacts"] == expect, (j["contacts"], expect)
assert j["ranks"] == ranks and len(j["per_rank"]) == ranks
assert sum(r["owned"] for r in j["per_rank"]) == j["n"]
assert j["ghosts"] <= j["shell_ghosts"]
PY
    cases=$((cases + 1))
  done
  echo "ok: $f ($expect pairs) on 1-4 ranks"
done 3<<'CASES'
3 3000 0.5 -3 10   periodic 11
3 3000 0.5 -3 10   walls    12
3 2000 0.3 -3 1000 periodic 13
3 2000 0.3 -2 1000 walls    14
3 big  -   -   1000 periodic 18
3 big  -   -   1000 walls    19
3 4000 0.6 0  100  periodic 15
2 3000 0.5 -3 100  periodic 16
2 3000 0.5 -3 100  walls    17
CASES

# Two threads per rank give the same pairs.
f=d3-periodic-w10-a-3.h5
"$mpiexec" -np 2 "$hgrid" pairs "$f" --sizes "$(sizes_of "$f")" --decompose --threads 2 | sort > got.txt
"$hgrid" pairs "$f" --sizes "$(sizes_of "$f")" --threads 1 | sort > serial.txt
cmp -s serial.txt got.txt || fail "2 ranks x 2 threads: pair set differs"

# Bad input: one line, status 2, reported once (by rank 0).
set +e
"$mpiexec" -np 3 "$hgrid" count "$f" --sizes 0.5,1 --decompose > out.txt 2> err.txt
rc=$?
set -e
[ "$rc" -eq 2 ] || fail "sizes below the largest diameter: exit $rc, expected 2"
[ "$(grep -c '^hgrid: error: ' err.txt)" -eq 1 ] || fail "sizes: expected one error line, got: $(cat err.txt)"
[ ! -s out.txt ] || fail "sizes: output written despite the error"
set +e
"$mpiexec" -np 2 "$hgrid" count "$f" --decompose > out.txt 2> err.txt
rc=$?
set -e
[ "$rc" -eq 2 ] && grep -q '^hgrid: error: sizes:' err.txt || fail "no sizes: exit $rc, $(cat err.txt)"
echo "decompose: $cases decomposed runs equal to the serial grid; bad input refused"
