#!/usr/bin/env python3
"""The pair excess next to a wall at first order in density (docs/MODEL.md
section 8, walls). Not run by CI; run by hand (needs python3-numpy, ~20 s):

    python3 tests/independent/wall_mediators.py

At first order in density the pair correlation of hard spheres is exact:
g(1, 2) = 1 + sum_c int rho_c(3) f_1c f_2c d3 outside contact, where f = -1
where two spheres overlap: a third sphere c that overlaps both holds the pair
together (the mediator). In the bulk the integral is rho_c times the lens
volume; next to a wall only the part of the lens where a c-centre may sit
counts. The excluded-volume model instead multiplies the bulk correlation by
the wall profiles (Kirkwood's superposition). This script computes, for a
level-1 particle (the smallest class) at height z1 above one wall and its
level-1 partners within 1.5 cells, the first-order excess with the wall over
the same excess without it (both weighted by the partner's wall profile),
for two mediator profiles: the first-order one (a step: rho_c where the
centre fits) and Percus-Yevick's (with the contact layers). Mixture: the
Fig. 12 alpha = -3, omega = 10, nu = 0.6 one, level-1 cell s1 = 3.6467.
"""
import numpy as np
from fig12_mixture import B, rho, s1, sig, wall_hhat, wall_profile

Y = wall_hhat(rho)
zz = np.arange(0.0, 40, 0.05)            # centre height above the wall
prof = np.array([wall_profile(Y, c, zz) for c in range(B)])


def disc_overlap(p, q, d):
    """Area of the intersection of discs of radii p, q whose centres are d apart."""
    p, q, d = np.broadcast_arrays(np.maximum(p, 0), np.maximum(q, 0), d)
    out = np.where(d <= np.abs(p - q), np.pi * np.minimum(p, q) ** 2, 0.0)
    m = (d > np.abs(p - q)) & (d < p + q) & (p > 0) & (q > 0)
    pp, qq, dd = p[m], q[m], d[m]
    c1 = np.clip((dd ** 2 + pp ** 2 - qq ** 2) / (2 * dd * pp), -1, 1)
    c2 = np.clip((dd ** 2 + qq ** 2 - pp ** 2) / (2 * dd * qq), -1, 1)
    k4 = (-dd + pp + qq) * (dd + pp - qq) * (dd - pp + qq) * (dd + pp + qq)
    out[m] = pp ** 2 * np.arccos(c1) + qq ** 2 * np.arccos(c2) - 0.5 * np.sqrt(np.maximum(k4, 0))
    return out


def first_order(s, z1, z2, d, mediators):
    """sum_c rho_c int (profile of c) over the lens where c overlaps both: 'bulk', 'step' or 'py'."""
    t = (np.arange(64) + 0.5) / 64
    tot = np.zeros(np.shape(z1))
    for c in range(B):
        R = (s + sig[c]) / 2
        lo, hi = np.maximum(z1, z2) - R, np.minimum(z1, z2) + R
        if mediators != "bulk":
            lo = np.maximum(lo, sig[c] / 2)
        z3 = lo[:, None] + (hi - lo)[:, None] * t
        A = disc_overlap(np.sqrt(np.maximum(R ** 2 - (z3 - z1[:, None]) ** 2, 0)),
                         np.sqrt(np.maximum(R ** 2 - (z3 - z2[:, None]) ** 2, 0)), d[:, None])
        if mediators == "py":
            A = A * np.interp(z3, zz, prof[c])
        tot += rho[c] * np.where(hi > lo, A.mean(1) * (hi - lo), 0.0)
    return tot


rng = np.random.default_rng(1)
M = 8000
s = sig[0]
print(f"smallest class, diameter {s:.3f}; contact density / bulk of classes "
      + ", ".join(f"{sig[c]:.1f}: {np.interp(sig[c] / 2 + 0.03, zz, prof[c]):.1f}" for c in range(0, B, 5)))
print("z1, first-order excess with the wall / without it: step mediators, PY mediators")
zs = [s / 2, s / 2 + 0.5, 2.5, 3.5, 5.0, 7.0, 9.0, 12.0]
ratios = []
for z in zs:
    u = rng.normal(size=(M, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    r = s + (1.5 * s1 - s) * rng.uniform(size=M)
    w = r ** 2                                   # uniform in r: weight r^2 for uniform in volume
    z1, z2 = np.full(M, z), z + u[:, 2] * r
    d = np.hypot(u[:, 0], u[:, 1]) * r
    w = w * np.interp(z2, zz, prof[0])           # the partner's own wall profile
    e0 = np.sum(w * first_order(s, z1, z2, d, "bulk"))
    ratios.append([np.sum(w * first_order(s, z1, z2, d, m)) / e0 for m in ("step", "py")])
    print(f"{z:5.2f}, {ratios[-1][0]:.3f}, {ratios[-1][1]:.3f}", flush=True)
ratios = np.array(ratios)
zw = np.linspace(s / 2, s1, 200)
pw = np.interp(zw, zz, prof[0])
avg = [np.sum(pw * np.interp(zw, zs, ratios[:, i])) / np.sum(pw) for i in range(2)]
print(f"first cell (z1 < s1), profile-weighted: step {avg[0]:.3f}, PY {avg[1]:.3f}")
