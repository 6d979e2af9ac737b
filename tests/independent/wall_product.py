#!/usr/bin/env python3
"""The Kirkwood product near a wall, integrated exactly (docs/MODEL.md section 8,
walls). Not run by CI; run by hand (needs python3-numpy, a few seconds):

    python3 tests/independent/wall_product.py

The excluded-volume model puts a walled window's Percus-Yevick excess in
proportion to its random-centre count: excess(x) = E_bulk * R(x) / R_bulk.
Here the same product form (partner density rho(1 + h_W(z)) times the bulk
h(r)) is integrated over the clipped own-level window of a level-1 particle
at height x above one wall, by Monte Carlo, for the Fig. 12 alpha = -3,
omega = 10, nu = 0.6 mixture at N = 3e4 (s_1 = 3.6467). It prints, per x,
the random count R(x), the exact excess and the model's proportional one.
Then the bulk level-1 own-level excess per random pair at lower packing
fractions (what a local-density approximation near the wall would use).
"""
import numpy as np
from excluded_pins import hhat, window_ft
from fig12_mixture import B, P, k, radial, rho, rho_w, s1, sig, sig_w, sw

lev1 = np.where(sig <= s1)[0]
Yw = np.empty(len(k))
Yb = np.empty(len(k))
for i0 in range(0, len(k), 500):
    H = hhat(k[i0:i0 + 500], rho_w, sig_w)
    Yw[i0:i0 + 500] = (H[:, lev1, B] * P[lev1]).sum(1) / P[lev1].sum()  # level 1's wall correlation
    Yb[i0:i0 + 500] = (H[:, 0, lev1] * rho[lev1]).sum(1)                 # smallest class against level 1


zz = np.arange(0.0, 30, 0.05)
hW = radial(Yw, sw / 2 + zz)
rr = np.arange(0.025, 12, 0.05)
Yr = radial(Yb, rr)
rhoL = rho[lev1].sum()
rng = np.random.default_rng(1)
M = 400000


def window(x):
    """Random count and product-form excess of a particle at height x: partners in
    level-1 cells i-1..i+1 (clipped at the wall) on that axis, 3 x 3 across."""
    i = int(np.floor(x / s1))
    lo, hi = max(0, i - 1) * s1, (i + 2) * s1
    t0 = rng.uniform(0, s1, (M, 2))
    ty = rng.uniform(-s1, 2 * s1, (M, 2))
    yz = rng.uniform(lo, hi, M)
    vol = (3 * s1) ** 2 * (hi - lo)
    d = np.sqrt(((ty - t0) ** 2).sum(1) + (yz - x) ** 2)
    p = np.where(yz < 1.1, 0.0, 1 + np.interp(yz, zz, hW, right=0))
    h = np.where(d < 2.05, -rhoL, np.interp(d, rr, Yr, left=-rhoL, right=0.0))
    return rhoL * np.mean(p) * vol, np.mean(p * h) * vol


Rb, Eb = window(60.0)
print(f"bulk: random {Rb:.3f}, excess {Eb:.3f}")
print("x, random, excess (product, exact), excess (model: proportional), ratio")
for x in [1.1, 1.3, 1.6, 2.0, 2.5, 3.0, 3.5, 4.5, 5.5, 6.5, 8.0, 10.0]:
    R, E = window(x)
    print(f"{x:.1f}, {R:.3f}, {E:.3f}, {Eb * R / Rb:.3f}, {E / (Eb * R / Rb):.3f}")

print("nu, level-1 own-level excess per random pair (smallest class, bulk)")
c = s = s1
kw = np.arange(1, int(30 / sig.min() / (0.5 * np.pi / (np.sqrt(3) * 2 * s1)))) * (0.5 * np.pi / (np.sqrt(3) * 2 * s1))
Wk = window_ft(kw, c, s)
for nu_l in [0.6, 0.5, 0.45, 0.3]:
    rho_l = nu_l / (np.pi / 6 * np.sum(P * sig ** 3)) * P
    Y = (hhat(kw, rho_l, sig)[:, 0, lev1] * rho_l[lev1]).sum(1)
    E = np.sum(kw ** 2 * Y * Wk) * (kw[1] - kw[0]) / (2 * np.pi ** 2)
    print(f"{nu_l:.2f}, {E / (rho_l[lev1].sum() * (2 * c + s) ** 3):.3f}")
