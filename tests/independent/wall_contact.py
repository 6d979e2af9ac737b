#!/usr/bin/env python3
"""Contact densities at a hard wall (docs/MODEL.md section 8, walls). Not run
by CI; run by hand (needs python3-numpy, ~10 s per nu):

    python3 tests/independent/wall_contact.py [NU [PACKING.xyz]]

For the Fig. 12 mixture (alpha = -3, omega = 10) at packing fraction NU
(default 0.6) it prints the sum of the contact densities at a wall from
Percus-Yevick's and from BMCSL's contact values, against the BMCSL pressure
beta P (the contact theorem makes the sum equal to beta P). Given a walled
packing as XYZ (`hgrid export FILE --xyz OUT`), it also prints, per radius
group, the measured density of centres at gaps from the wall (over the
bulk density, counted more than 25 from every wall) against PY's wall
profile averaged over the same gaps.
"""
import sys
import numpy as np
import fig12_mixture as M

nu = float(sys.argv[1]) if len(sys.argv) > 1 else 0.6
rho = M.rho * nu / M.nu
s = M.sig
xi = [np.pi / 6 * np.sum(rho * s ** m) for m in range(4)]
e = 1 - xi[3]
g_py = 1 / e + 3 * xi[2] * s / e ** 2                   # Lebowitz's contact value, partner of infinite size
g_bmcsl = g_py + 2 * xi[2] ** 2 * s ** 2 / e ** 3
beta_p = M.bmcsl_pressure(rho, s)
print(f"nu {nu}: sum of contact densities PY {np.sum(rho * g_py):.4f}, BMCSL {np.sum(rho * g_bmcsl):.4f}; "
      f"beta P (BMCSL) {beta_p:.4f}")
groups = [(1, 1.5), (1.5, 2.5), (2.5, 4), (4, 6), (6, 10.01)]
for lo, hi in groups:
    c = [i for i in range(M.B) if lo <= s[i] / 2 < hi]
    w = M.P[c] / M.P[c].sum()
    print(f"  radii {lo}-{hi}: contact value PY {np.sum(w * g_py[c]):.2f}, BMCSL {np.sum(w * g_bmcsl[c]):.2f}")
if len(sys.argv) < 3:
    sys.exit(0)

Y = M.wall_hhat(rho)
gap = np.arange(0.0, 12, 0.01)
lines = open(sys.argv[2]).readlines()
L = float(lines[1].split('"')[1].split()[0])
a = np.loadtxt(sys.argv[2], skiprows=2, usecols=(1, 2, 3, 4))
x, r = a[:, :3], a[:, 3]
bins = [0, 0.1, 0.3, 0.6, 1, 2, 3, 5, 8]
print("gap bins " + " ".join(f"[{bins[i]},{bins[i + 1]})" for i in range(len(bins) - 1)) + ": measured / PY")
for lo, hi in groups:
    m = (r >= lo) & (r < hi)
    h = np.concatenate([x[m], L - x[m]], axis=1).ravel()   # centre heights above the six walls
    g = h - np.repeat(r[m], 6)
    bulk = np.sum((h > 25) & (h < L - 25)) / (L - 50)
    meas = np.histogram(g, bins)[0] / np.diff(bins) / bulk
    c = [i for i in range(M.B) if lo <= s[i] / 2 < hi]
    w = M.P[c] / M.P[c].sum()
    py = sum(wc * M.wall_profile(Y, i, s[i] / 2 + gap) for i, wc in zip(c, w))
    pyb = [py[(gap >= bins[i]) & (gap < bins[i + 1])].mean() for i in range(len(bins) - 1)]
    print(f"  radii {lo}-{hi} ({m.sum()}): " + " ".join(f"{meas[i]:.1f}/{pyb[i]:.1f}" for i in range(len(bins) - 1)))
