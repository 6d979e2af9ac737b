#!/usr/bin/env bash
# Near a wall, do pairs carry the bulk's pair excess? The excluded-volume
# model (docs/MODEL.md section 8) puts each window's Percus-Yevick excess in
# proportion to its random-centre count, the same share everywhere in a
# walled box. This measures, in 3D packings (alpha = -3, omega = 10,
# nu = 0.6, seed 1, as placed and after 10^4 Monte Carlo sweeps), the
# lowest level's own-level checks (pairs of level-1 particles in the same or
# adjacent level-1 cells, exactly what the grid counts, for the sizes
# `hgrid count --cells optimal` picks) against what independent centres
# would give with the packing's own one-particle profiles (the product of
# the three axes' measured cell occupancies). Pairs are split into those with
# a particle in a cell touching a wall and the rest (interior; periodic
# boxes: cells of side s_1 without the wrap-around pairs, a ratio all the
# same). The ratio measured / independent is 1 + the pair excess that the
# packing carries.
# Writes results/wall_pairs.csv and prints a Markdown table.
# Usage: plots/wall_pairs.sh   (~10 s once the packings are cached;
# generating the two N = 3e4 equilibrated ones takes ~6 min more on 2 cores;
# needs python3 with numpy)
set -euo pipefail
cd "$(dirname "$0")/.."
script=plots/wall_pairs.sh
csv=results/wall_pairs.csv
. plots/lib/packing_stats.sh
{
  echo "# 3D excluded-volume packings (alpha = -3, omega = 10, nu = 0.6, seed 1): level-1 own-level checks, measured against independent centres with the packing's measured axis profiles; wall = pairs with a particle in a cell touching a wall"
  stamp
  echo "boundary,n,sweeps,s1,level1_particles,pairs,measured,independent,ratio"
  for point in "walls 3000 0" "walls 3000 10000" "walls 30000 0" "walls 30000 10000" "periodic 30000 0" "periodic 30000 10000"; do
    read -r boundary n sweeps <<<"$point"
    echo "plots/wall_pairs.sh: $boundary N = $n, $sweeps sweeps" >&2
    file=$(xyz "$boundary" "$n" "$sweeps" "$work/p.xyz")
    s1=$("$hgrid" count "$file" --cells optimal --json | "$py" -c 'import json, sys; print(repr(json.load(sys.stdin)["sizes"][0]))')
    "$py" - "$work/p.xyz" "$boundary" "$n" "$sweeps" "$s1" <<'EOF'
import sys
import numpy as np
path, boundary, n_arg, sweeps, s1 = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5])
with open(path) as f:
    n = int(f.readline())
    side = float(f.readline().split('"')[1].split()[0])  # cubic box
    data = np.loadtxt(f, usecols=(1, 2, 3, 4), max_rows=n)
x = data[:, :3][2 * data[:, 3] <= s1]  # level 1: diameter <= s1
N1 = len(x)
nc = int(np.ceil(side / s1))
cell = np.clip(np.floor(x / s1).astype(int), 0, nc - 1)
occ = np.zeros((nc, nc, nc))
np.add.at(occ, tuple(cell.T), 1.0)
prof = [np.bincount(cell[:, k], minlength=nc) / N1 for k in range(3)]
ind = N1 * (N1 - 1) * np.einsum('i,j,k->ijk', *prof)  # independent centres: expected ordered pairs per cell pair / occupancy
edge1 = np.zeros(nc, bool)
if boundary == 'walls':
    edge1[0] = edge1[-1] = True
wall = edge1[:, None, None] | edge1[None, :, None] | edge1[None, None, :]
out = {'interior': [0.0, 0.0], 'wall': [0.0, 0.0]}
offsets = [(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1) if (a, b, c) >= (0, 0, 0)]
for o in offsets:
    src = tuple(slice(max(0, -d), nc - max(0, d)) for d in o)
    dst = tuple(slice(max(0, d), nc - max(0, -d)) for d in o)
    if o == (0, 0, 0):
        meas = 0.5 * occ * (occ - 1)
        expd = 0.5 * ind * np.einsum('i,j,k->ijk', *prof)
        w = wall
    else:
        meas = occ[src] * occ[dst]
        pa = np.einsum('i,j,k->ijk', *[p[s] for p, s in zip(prof, src)])
        pb = np.einsum('i,j,k->ijk', *[p[s] for p, s in zip(prof, dst)])
        expd = N1 * (N1 - 1) * pa * pb
        w = wall[src] | wall[dst]
    for key, m in (('interior', ~w), ('wall', w)):
        out[key][0] += meas[m].sum()
        out[key][1] += expd[m].sum()
for key in ('interior', 'wall'):
    if boundary == 'periodic' and key == 'wall':
        continue
    m, e = out[key]
    print(f"{boundary},{n_arg},{sweeps},{s1:.4f},{N1},{key},{m:.0f},{e:.0f},{m / e:.3f}")
EOF
  done
} >"$tmp"
mv "$tmp" "$csv"
echo "| boundary | N | sweeps | s_1 | level-1 particles | pairs | measured | independent | ratio |"
echo "|---|---|---|---|---|---|---|---|---|"
grep -v '^#' "$csv" | tail -n +2 | sed 's/,/ | /g; s/^/| /; s/$/ |/'
