#!/usr/bin/env python3
"""Independent evaluation of the excluded-volume model's excess (docs/MODEL.md
section 8) for the pinned points of tests/test_excluded_model.cpp.

Written separately from the C++: numpy/LAPACK inverse of Q^T(-k) Q(k) with
closed-form Q integrals, and the window's spherical average transformed in
k-space (instead of a sine transform of h). Not run by CI; run by hand:

    python3 tests/independent/excluded_pins.py      # needs python3-numpy

It prints the excess of T_cd/N over the paper's model for each case.
"""
import numpy as np

M = 400
_i = np.arange(M) + 0.5
_ph = np.arccos(1 - 2 * _i / M)
_th = np.pi * (1 + 5 ** 0.5) * _i
DIRS = np.stack([np.cos(_th) * np.sin(_ph), np.sin(_th) * np.sin(_ph), np.cos(_ph)], 1)


def shell_area(rho, c, s):
    w = np.prod(np.clip((c + s - np.abs(rho[:, None, None] * DIRS[None, :, :])) / s, 0, 1), axis=2).mean(1)
    return 4 * np.pi * rho ** 2 * w


def window_ft(k, c, s, nr=1500):
    """Spherical average of the window's Fourier transform."""
    R = np.sqrt(3) * (c + s)
    r = np.linspace(0, R, nr + 1)[1:] - R / nr / 2
    A = shell_area(r, c, s)
    out = np.empty(len(k))
    for i0 in range(0, len(k), 2000):
        kk = k[i0:i0 + 2000]
        out[i0:i0 + 2000] = (np.sinc(np.outer(kk, r) / np.pi) @ A) * (R / nr)
    return out


def hhat(k, rho, sig):
    """hhat_ab(k) of the Percus-Yevick mixture (Baxter's Q function)."""
    xi = [np.pi / 6 * np.sum(rho * sig ** n) for n in range(4)]
    e = 1 - xi[3]
    a = (1 - xi[3] + 3 * sig * xi[2]) / e ** 2
    b = -3 * sig ** 2 * xi[2] / (2 * e ** 2)
    R = (sig[:, None] + sig[None, :]) / 2
    S = (sig[:, None] - sig[None, :]) / 2
    A, B = a[:, None], b[:, None]
    kk = k[:, None, None]

    def P0(x): return np.exp(1j * kk * x) / (1j * kk)
    def P1(x): return np.exp(1j * kk * x) * (x / (1j * kk) + 1 / kk ** 2)
    def P2(x): return np.exp(1j * kk * x) * (x ** 2 / (1j * kk) + 2 * x / kk ** 2 - 2 / (1j * kk ** 3))

    integral = A / 2 * (P2(R) - P2(S)) + B * (P1(R) - P1(S)) - (A / 2 * R ** 2 + B * R) * (P0(R) - P0(S))
    sq = np.sqrt(rho[:, None] * rho[None, :])
    Q = np.eye(len(rho))[None] - 2 * np.pi * sq[None] * integral
    ImC = np.conj(Q).transpose(0, 2, 1) @ Q
    H = np.linalg.inv(ImC) - np.eye(len(rho))[None]
    return H.real / sq[None]


def moment(i, lo, hi, alpha, rmax):
    def prim(x, p): return np.log(x) if abs(p + 1) < 1e-14 else x ** (p + 1) / (p + 1)
    C = 1 / (prim(rmax, alpha) - prim(1.0, alpha))
    return C * (prim(hi, alpha + i) - prim(lo, alpha + i))


def size_classes(alpha, omega, sizes, B, d):
    """B geometric classes per level: probability, mean radius, diameter keeping the mean r^d, level."""
    P, rm, sg, lv = [], [], [], []
    lo = 1.0
    for h in range(len(sizes)):
        hi = min(sizes[h] / 2, omega)
        if hi > lo:
            e = lo * (hi / lo) ** (np.arange(B + 1) / B)
            e[-1] = hi
            for q in range(B):
                p = moment(0, e[q], e[q + 1], alpha, omega)
                P.append(p)
                rm.append(moment(1, e[q], e[q + 1], alpha, omega) / p)
                sg.append(2 * (moment(d, e[q], e[q + 1], alpha, omega) / p) ** (1 / d))
                lv.append(h)
            lo = hi
    return map(np.array, (P, rm, sg, lv))


def windows(rm, lv, sizes):
    """Top-Down: each class's own level (half: pairs once) and the levels below."""
    win = []
    for a in range(len(rm)):
        win.append((a, lv[a], sizes[lv[a]], sizes[lv[a]], 0.5))
        win += [(a, j, rm[a] + sizes[j] / 2, sizes[j], 1.0) for j in range(lv[a])]
    return win


def excess(alpha, omega, nu, sizes, B=6, kmax_fac=15, dk_fac=0.5):
    c = nu / (4 / 3 * np.pi * moment(3, 1.0, omega, alpha, omega))
    P, rm, sg, lv = size_classes(alpha, omega, sizes, B, 3)
    rho = c * P
    win = windows(rm, lv, sizes)
    reach = max(np.sqrt(3) * (w[2] + w[3]) for w in win)
    kmax, dk = kmax_fac / sg.min(), dk_fac * np.pi / reach / 2
    k = np.arange(1, int(kmax / dk)) * dk
    H = np.concatenate([hhat(k[i:i + 500], rho, sg) for i in range(0, len(k), 500)])
    total = 0.0
    for a, j, cc, s, half in win:
        bs = lv == j
        total += half * P[a] * np.sum(k ** 2 * dk / (2 * np.pi ** 2) * window_ft(k, cc, s) * (H[:, a, bs] @ rho[bs]))
    return total


if __name__ == "__main__":
    for case in [(-3, 10, 0.4, [4.0, 8.0, 20.0]), (-3, 100, 0.6, [6.0, 14.0, 30.0, 70.0, 200.0]),
                 (0, 10, 0.5, [5.0, 12.0, 20.0])]:
        print("alpha %g omega %g nu %g sizes %s: excess T_cd/N = %.6f" % (case[0], case[1], case[2], case[3], excess(*case)))
