#!/usr/bin/env python3
"""Independent evaluation of the excluded-volume model in a box with walls
(docs/MODEL.md section 8, walls) for the pinned points of
tests/test_excluded_model.cpp (ExcludedModel.WallsMatchAnIndependentEvaluation).
Not run by CI; run by hand (needs python3-numpy, ~2 min):

    python3 tests/independent/walled_pins.py

Written from MODEL.md, separately from src/model/excluded.cpp and
src/model/detail/walls.cpp:
- wall profiles: the wall is a Percus-Yevick component 20 largest diameters
  wide at a negligible density; h_cW(r) by a direct sine sum (matrix product)
  on a k grid twice as long as the C++ one, the contact step taken out in
  closed form (fig12_mixture.py's construction, parametrised here) and added
  back exactly where the profile is read (a table interpolated across the
  jump at contact would smear it: 1e-3 of T/N at a 0.01 step);
- each axis: the classes' densities 1 + h(x) + h(A - x) on a uniform grid,
  their cumulative integrals by the trapezoid rule, the scanning position
  integrated over the same grid (the C++ uses a midpoint rule and linear
  interpolation of a cumulative sum);
- the bulk excess per window by the window's spherical average transformed in
  k-space (excluded_pins.py), not by a sine transform of h.
It prints T/N, T_cd/N and T_ca/N for each case, the depleted wall layer and
Kirkwood's product.
"""
import numpy as np
from excluded_pins import hhat, size_classes, window_ft, windows

WALL_DIAMETER = 20.0  # in largest diameters
WALL_PACKING = 1e-12
WALL_REACH = 4.0      # profiles tabulated this many largest diameters from the wall


def wall_contact_values(rho, sg, sw):
    """PY contact values of each class against a wall sphere of diameter sw."""
    xi2, xi3 = np.pi / 6 * np.sum(rho * sg ** 2), np.pi / 6 * np.sum(rho * sg ** 3)
    return 1 / (1 - xi3) + 3 * xi2 * (sg * sw / (sg + sw)) / (1 - xi3) ** 2


def contact_step(R, g, lam, r):
    """The step of h_cW at contact R: -1 inside, (g - 1) e^{-(r - R)/lam} outside."""
    return np.where(r < R, -1.0, (g - 1) * np.exp(-np.maximum(r - R, 0) / lam))


def contact_step_hat(R, g, lam, q):
    """Its 3D Fourier transform, in closed form, at wave numbers q."""
    inside = -(np.sin(q * R) - q * R * np.cos(q * R)) / q ** 2
    zc = 1 / lam - 1j * q
    outside = (np.exp(1j * q * R) * (1 / zc ** 2 + R / zc)).imag
    return 4 * np.pi / q * (inside + (g - 1) * outside)


def wall_profiles(rho, sg):
    """Per class c, a function z -> rho_c(z) / rho_c at centre distance z from one wall."""
    B = len(rho)
    sw = WALL_DIAMETER * sg.max()
    rho_w = np.append(rho, WALL_PACKING * 6 / (np.pi * sw ** 3))
    sig_w = np.append(sg, sw)
    dk = 0.25 * np.pi / (sw / 2 + WALL_REACH * sg.max())
    k = np.arange(1, int(30 / sg.min() / dk)) * dk
    Y = np.concatenate([hhat(k[i:i + 400], rho_w, sig_w)[:, :B, B] for i in range(0, len(k), 400)])
    g = wall_contact_values(rho, sg, sw)
    lam = sg.min() / 2
    R = (sg + sw) / 2
    for c in range(B):  # the step at contact, transformed in closed form
        Y[:, c] -= contact_step_hat(R[c], g[c], lam, k)
    zt = np.arange(0.0, WALL_REACH * sg.max(), 0.01)
    r = sw / 2 + zt
    S = np.sin(np.outer(r, k)) * (dk / (2 * np.pi ** 2)) / r[:, None]
    smooth = [S @ (k * Y[:, c]) for c in range(B)]  # continuous: tabulated; the step added exactly

    def make(c):
        def h(z):
            out = np.interp(z, zt, smooth[c], right=0.0) + contact_step(R[c], g[c], lam, sw / 2 + z)
            return np.where(z < sg[c] / 2, -1.0, np.where(z > zt[-1], 0.0, out))
        return h
    return [make(c) for c in range(B)]


class Axis:
    """One axis [0, A] with walls: the classes' normalised densities and CDFs on a grid."""

    def __init__(self, A, hw, sg, M=400000):
        self.A = A
        self.x = np.linspace(0.0, A, M + 1)
        self.dens, self.cdf = [], []
        for c in range(len(sg)):
            n = np.maximum(0.0, 1 + hw[c](self.x) + hw[c](A - self.x))
            n[(self.x < sg[c] / 2) | (self.x > A - sg[c] / 2)] = 0.0
            cum = np.concatenate([[0.0], np.cumsum((n[1:] + n[:-1]) / 2)])
            self.dens.append(n / cum[-1])
            self.cdf.append(cum / cum[-1])

    def scan(self, a, s, own, beta, searched, layer):
        """Averages over the scanning class a's positions: cells scanned, cell below /
        above present (own level), and per searched class the share of its centres
        inside the scan (all scanning positions, and those >= layer from both walls)."""
        x, w = self.x, self.dens[a]
        wt = w.copy()  # trapezoid weights on the uniform grid
        wt[[0, -1]] /= 2
        wt /= wt.sum()
        n = max(1, int(np.ceil(self.A / s)))
        cell = lambda y: np.clip(np.floor(y / s).astype(np.int64), 0, n - 1)
        if own:
            i = cell(x)
            c0, c1 = np.maximum(0, i - 1), np.minimum(n - 1, i + 1)
            below, above = np.sum(wt * (i >= 1)), np.sum(wt * (i <= n - 2))
        else:
            c0, c1 = cell(x - beta), cell(x + beta)
            below = above = 0.0
        inner = (x >= layer) & (x <= self.A - layer)
        frac, frac_in = [], []
        for q in searched:
            f = np.interp(np.minimum((c1 + 1) * s, self.A), x, self.cdf[q]) - np.interp(c0 * s, x, self.cdf[q])
            frac.append(np.sum(wt * f))
            frac_in.append(np.sum(wt * f * inner))
        return np.sum(wt * (c1 - c0 + 1)), below, above, np.array(frac), np.array(frac_in)


def walled(alpha, omega, nu, sizes, A, layer_mode=True, K=0.2, B=6):
    P, rm, sg, lv = size_classes(alpha, omega, sizes, B, 3)
    cdens = nu / (np.pi / 6 * np.sum(P * sg ** 3))  # the model's mean volume keeps each class's r^3
    rho = cdens * P
    win = windows(rm, lv, sizes)
    reach = max(np.sqrt(3) * (w[2] + w[3]) for w in win)
    kmax, dk = 15 / sg.min(), 0.25 * np.pi / reach
    k = np.arange(1, int(kmax / dk)) * dk
    H = np.concatenate([hhat(k[i:i + 500], rho, sg) for i in range(0, len(k), 500)])
    hw = wall_profiles(rho, sg)
    ax = Axis(A, hw, sg)
    layer = rm.max() if layer_mode else 0.0
    Tcd, Tca = 0.0, 0.0
    for a, j, cc, s, half in win:
        bs = np.where(lv == j)[0]
        E = np.sum(k ** 2 * dk / (2 * np.pi ** 2) * window_ft(k, cc, s) * (H[:, a, bs] @ rho[bs]))
        own = j == lv[a]
        cells, below, above, fr, fi = ax.scan(a, s, own, cc, bs, layer)
        random = cdens * A ** 3 * np.sum(P[bs] * fr ** 3)
        interior = cdens * A ** 3 * np.sum(P[bs] * fi ** 3)
        bulk = cdens * P[bs].sum() * (2 * cc + s) ** 3
        Tcd += half * P[a] * (random + E * interior / bulk)
        if own:  # own cell and the half stencil's existing cells (first non-zero offset positive)
            pr = {-1: below, 0: 1.0, 1: above}
            t = 0.0
            for o in np.ndindex(3, 3, 3):
                o = [v - 1 for v in o]
                first = next((v for v in o if v != 0), 0)
                if first >= 0:
                    t += pr[o[0]] * pr[o[1]] * pr[o[2]]
            Tca += P[a] * t
        else:
            Tca += P[a] * cells ** 3
    return Tcd + K * Tca, Tcd, Tca


if __name__ == "__main__":
    # Note on the scan of a cross-level window: the scanning class a's position on
    # one axis is averaged with a's density; the three axes are independent (a
    # cubic box: the same average cubed, as the searched class's share is).
    cases = [(-3, 10, 0.4, [4.0, 8.0, 20.0], 60.0),
             (-3, 10, 0.6, [3.71, 6.29, 9.67, 14.14, 20.0], 72.5),
             (0, 10, 0.5, [5.0, 12.0, 20.0], 80.0)]
    for alpha, omega, nu, sizes, A in cases:
        for mode in (True, False):
            t, cd, ca = walled(alpha, omega, nu, sizes, A, mode)
            print("alpha %g omega %g nu %g sizes %s A %g %s: T/N = %.6f (T_cd/N %.6f, T_ca/N %.6f)"
                  % (alpha, omega, nu, sizes, A, "layer  " if mode else "product", t, cd, ca))
