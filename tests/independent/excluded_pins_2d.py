#!/usr/bin/env python3
"""Independent evaluation of the 2D excluded-volume model's excess (docs/MODEL.md
section 8, "Discs") for the pinned points of tests/test_excluded_model.cpp.

Written separately from the C++ (model/detail/py_numeric.cpp, excluded.cpp):
- J0 and J1 from their integral representations (trapezoid rule in the angle,
  exact to rounding for these arguments), not GSL;
- each pair's contact interval [0, sigma_ab] on its own grid of 2 n + 1 nodes
  (Simpson's rule), not a shared r step with a trapezoid;
- the fixed point by plain Picard mixing (no Anderson), with the same
  density continuation idea but fixed steps;
- the window's circle integral at every r by direct angle averaging.
Not run by CI; run by hand:

    python3 tests/independent/excluded_pins_2d.py      # needs python3-numpy

It prints the excess of T_cd/N over the paper's model for each case.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from excluded_pins import moment, size_classes, windows  # noqa: E402  (binning and windows shared with the 3D script)

NTH = 1024  # angles of the integral representation of J1


def j0(x):
    """J0 from its power series (x < 20) and Hankel's asymptotic expansion (x >= 20)."""
    x = np.asarray(x, float)
    out = np.empty_like(x)
    small = x < 20
    xs = x[small]
    term = np.ones_like(xs)
    tot = term.copy()
    q = (xs / 2) ** 2
    for m in range(1, 90):
        term = -term * q / (m * m)
        tot += term
    out[small] = tot
    xl = x[~small]
    P, Q = np.ones_like(xl), np.zeros_like(xl)
    a = 1.0
    for k in range(1, 30):
        a *= (2 * k - 1) ** 2 / (k * 8.0)  # |a_k(0)|
        t = a / xl ** k
        if k % 2:
            Q += (-1) ** ((k - 1) // 2 + 1) * t
        else:
            P += (-1) ** (k // 2) * t
    out[~small] = np.sqrt(2 / (np.pi * xl)) * (P * np.cos(xl - np.pi / 4) - Q * np.sin(xl - np.pi / 4))
    return out


def j0_integral(x):
    th = (np.arange(4096) + 0.5) * np.pi / 4096
    return np.cos(np.outer(x, np.sin(th))).mean(1)


def j1(x):
    th = (np.arange(NTH) + 0.5) * np.pi / NTH
    return np.cos(th[None, :] - np.outer(x, np.sin(th))).mean(1)


def j0_zeros(n):
    """First n zeros of J0: McMahon's estimate refined by Newton (J0' = -J1)."""
    m = np.arange(1, n + 1)
    b = (m - 0.25) * np.pi
    z = b + 1 / (8 * b) - 31 / (384 * b ** 3)
    for _ in range(6):
        z = z + j0(z) / j1(z)
    return z


def simpson_weights(n2):
    w = np.ones(n2 + 1)
    w[1:-1:2] = 4
    w[2:-1:2] = 2
    return w / 3


def solve_py(rho, sig, R, nk, nodes=200, steps=(0.2, 0.4, 0.6, 0.8, 1.0), tol=1e-7):
    M = len(rho)
    z = j0_zeros(nk)
    k = z / R
    kw = 1 / (np.pi * R ** 2 * j1(z) ** 2)
    pairs = [(a, b) for a in range(M) for b in range(a, M)]
    grids, fwd, inv = [], [], []
    for a, b in pairs:
        s = (sig[a] + sig[b]) / 2
        n2 = 2 * max(nodes // 2, int(np.ceil(s / 0.01 / 2)))
        r = np.linspace(0, s, n2 + 1)
        T = j0(np.outer(k, r))  # nk x nodes
        grids.append(r)
        fwd.append(T * (2 * np.pi * r * simpson_weights(n2) * s / n2)[None, :])
        inv.append(T.T * kw[None, :])
    g = [np.zeros(len(r)) for r in grids]
    for t in steps:
        for it in range(20000):
            C = np.zeros((nk, M, M))
            for p, (a, b) in enumerate(pairs):
                C[:, a, b] = C[:, b, a] = fwd[p] @ (-(1 + g[p]))
            Rm = t * np.diag(rho)
            A = np.eye(M)[None] - C @ Rm[None]
            G = np.linalg.solve(A, C @ Rm[None] @ C)
            G = (G + G.transpose(0, 2, 1)) / 2
            diff = 0.0
            for p, (a, b) in enumerate(pairs):
                new = inv[p] @ G[:, a, b]
                diff = max(diff, np.abs(new - g[p]).max())
                g[p] = g[p] + 0.3 * (new - g[p])
            if diff < (tol if t == 1.0 else 1e-4):
                break
        else:
            raise RuntimeError("no convergence at t = %g" % t)
    return k, kw, pairs, grids, g, G


def circle_length(r, c, s):
    th = (np.arange(2000) + 0.5) * (np.pi / 2) / 2000
    w1 = np.clip((c + s - np.abs(np.outer(r, np.cos(th)))) / s, 0, 1)
    w2 = np.clip((c + s - np.abs(np.outer(r, np.sin(th)))) / s, 0, 1)
    return 2 * np.pi * r * (w1 * w2).mean(1)


def excess(alpha, omega, nu, sizes, B=4, kmax_fac=15, range_fac=3):
    c = nu / (np.pi * moment(2, 1.0, omega, alpha, omega))
    P, rm, sg, lv = size_classes(alpha, omega, sizes, B, 2)
    rho = c * P
    win = windows(rm, lv, sizes)
    reach = max(np.sqrt(2) * (w[2] + w[3]) for w in win)
    R = reach + range_fac * sg.max()
    nk = int(np.ceil(kmax_fac / sg.min() * R / np.pi))
    k, kw, pairs, grids, g, G = solve_py(rho, sg, R, nk)
    # gamma_ab(r) on one grid over [0, reach] for every pair (inverse series).
    nr = 3000
    rr = np.linspace(0, reach, nr + 1)
    T = j0(np.outer(rr, k)) * kw[None, :]
    gam = {}
    for p, (a, b) in enumerate(pairs):
        gam[(a, b)] = gam[(b, a)] = T @ G[:, a, b]
    total = 0.0
    for a, j, cc, s, half in win:
        Lw = circle_length(rr, cc, s)
        x = 0.0
        for b in range(len(P)):
            if lv[b] != j:
                continue
            p = pairs.index((min(a, b), max(a, b)))
            sab = (sg[a] + sg[b]) / 2
            # inside contact h = -1: Simpson on [0, sigma_ab]
            ri = np.linspace(0, sab, 2001)
            inside = -np.sum(simpson_weights(2000) * circle_length(ri, cc, s)) * sab / 2000
            # outside h = gamma: trapezoid on the grid beyond sigma_ab, plus the
            # piece from sigma_ab (gamma there from the contact solution) to the first node
            o = rr > sab
            f = gam[(a, b)][o] * Lw[o]
            outside = np.trapz(f, rr[o]) if f.size > 1 else 0.0
            if f.size:
                f0 = g[p][-1] * circle_length(np.array([sab]), cc, s)[0]
                outside += 0.5 * (f0 + f[0]) * (rr[o][0] - sab)
            x += rho[b] * (inside + outside)
        total += half * P[a] * x
    return total


if __name__ == "__main__":
    xs = np.array([0.1, 3.0, 19.9, 20.1, 57.3, 400.0])
    assert np.abs(j0(xs) - j0_integral(xs)).max() < 1e-9, (j0(xs), j0_integral(xs))
    for case in [(-3, 10, 0.4, [4, 8, 20]), (-3, 10, 0.6, [4, 8, 20]), (0, 5, 0.5, [3, 10])]:
        print(case, "%.6f" % excess(*case))
