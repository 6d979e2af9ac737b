#!/usr/bin/env bash
# Where walls meet: does the excluded-volume model's product of three 1D wall
# profiles (docs/MODEL.md section 8) hold at the box's edges? For each size
# class of a walled 3D packing (alpha = -3, omega = 10, nu = 0.6, seed 1),
# u_k = the distance of a centre to the nearer wall on axis k. Per axis, the
# share of the class within the wall layer (u_k < c: c = 2.5 for radii below
# 1.5, 4 for radii 1.5 to 3); per pair of axes, the share within both layers
# (an edge), measured, against the product of the two per-axis shares (what
# the model's product form puts there). Writes results/wall_edges.csv and
# prints it as a Markdown table.
# Usage: plots/wall_edges.sh   (~1 min on 2 cores; needs python3 with numpy)
set -euo pipefail
cd "$(dirname "$0")/.."
script=plots/wall_edges.sh
csv=results/wall_edges.csv
. plots/lib/packing_stats.sh
{
  echo "# walled 3D excluded-volume packings (alpha = -3, omega = 10, nu = 0.6, seed 1): share of each size class near one wall and near two (an edge), against the product of the per-axis shares"
  stamp
  echo "n,sweeps,radii,particles,layer,share_per_axis,edge_measured,edge_product,edge_ratio"
  for point in "3000 0" "3000 10000" "30000 0"; do
    read -r n sweeps <<<"$point"
    xyz walls "$n" "$sweeps" "$work/p.xyz" >/dev/null
    "$py" - "$work/p.xyz" "$n" "$sweeps" <<'EOF'
import sys
import numpy as np
path, n_arg, sweeps = sys.argv[1:4]
with open(path) as f:
    n = int(f.readline())
    side = float(f.readline().split('"')[1].split()[0])  # cubic box
    data = np.loadtxt(f, usecols=(1, 2, 3, 4), max_rows=n)
u = np.minimum(data[:, :3], side - data[:, :3])
r = data[:, 3]
for lo, hi, layer in ((1.0, 1.5, 2.5), (1.5, 3.0, 4.0)):
    cls = u[(r >= lo) & (r < hi)] < layer
    per_axis = cls.mean()
    edge = np.mean([np.mean(cls[:, a] & cls[:, b]) for a, b in ((0, 1), (0, 2), (1, 2))])
    print(f"{n_arg},{sweeps},{lo}-{hi},{len(cls)},{layer},{per_axis:.4f},{edge:.4f},{per_axis**2:.4f},{edge / per_axis**2:.3f}")
EOF
  done
} >"$tmp"
mv "$tmp" "$csv"
echo "| N | sweeps | radii | particles | layer | share per axis | edge, measured | edge, product | ratio |"
echo "|---|---|---|---|---|---|---|---|---|"
grep -v '^#' "$csv" | tail -n +2 | sed 's/,/ | /g; s/^/| /; s/$/ |/'
