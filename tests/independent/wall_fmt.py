#!/usr/bin/env python3
"""Planar hard-wall density profiles of the Fig. 12 polydisperse hard-sphere mixture
(30 classes, tests/independent/fig12_mixture.py) from White-Bear (mark I)
fundamental-measure theory (Roth, Evans, Lang, Kahl 2002; Rosenfeld 1989), for
docs/MODEL.md section 8, walls. Not run by CI; run by hand (numpy only):

    OMP_NUM_THREADS=1 nice -n 19 python3 wall_fmt.py [--dz 0.02] [--Z 100] [--nus 0.4,0.5,0.6]
                                                      [--out .] [--tol 1e-6]

Model.  Wall at z = 0; the centre of class i (radius R_i) may sit at z >= R_i.
Grid z_j = j dz, 0 <= z_j <= Z + 2 Rmax; rho_i = rho_b,i (bulk reservoir) for z_j > Z.
Weighted densities n_a(z) = sum_i sum_j rho_i(z_j) q_ij W_a,i(z - z_j) with the planar
FMT kernels (w3 = pi (R^2 - u^2), w2 = 2 pi R, w1 = w2/(4 pi R), w0 = w2/(4 pi R^2),
w2v = 2 pi u, w1v = w2v/(4 pi R), |u| < R) averaged exactly over each grid cell, and
q_ij = dz except at each class's first accessible point, where the cell is stretched
down to z = R_i (so the hard-wall step sits at R_i to O(dz^2)).  The discrete free
energy is minimised exactly: the Euler-Lagrange equation solved is
    ln(rho_i(z_j)/rho_b,i) = mu_ex,i - dz sum_m sum_a dPhi/dn_a(z_m) W_a,i(z_m - z_j),
with mu_ex,i from the same (exactly normalised) kernels in the bulk.

Solver.  Unknowns x = ln(rho/rho_b) at accessible points; continuation in nu
0.1, 0.2, 0.3, then steps of 0.02 (secant predictor); at each nu 30 safeguarded
Anderson steps, then inexact
Newton-GMRES (Jacobian-vector products by finite differences of the residual,
restarted GMRES written here) with a backtracking line search that rejects any step
giving n3 >= 1 anywhere.  Converged when max |residual| < tol (default 1e-6).

Prints, per nu: Newton iterations, time, final max residual; the contact theorem
(sum_i rho_i(R_i) against beta P of BMCSL, which is White Bear's bulk pressure);
contact values rho_i(R_i)/rho_b,i averaged (weights M.P) over the radius groups of
wall_contact.py; and the excess adsorption Gamma_i = int_0^inf (rho_i/rho_b,i - 1) dz
for the smallest, a middle and the largest class; max |rho/rho_b - 1| just before Z.
Saves fmt_profile_NU.npy (fmt_profile_NU_dzDZ.npy if dz != 0.02) into --out: rows z,
then rho_i(z)/rho_b,i for the 30 classes (0 below contact, 1 beyond Z).
Timing (dz 0.02, 1 busy core): the whole continuation 0.1 -> 0.6 takes ~1 min;
dz 0.01 ~2 min, dz 0.005 ~4 min.
"""
import sys, time, argparse
import numpy as np
import os
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fig12_mixture as M

# ---------------------------------------------------------------- White Bear mark I
def _G(x):
    """G(x) = [x + (1-x)^2 ln(1-x)] / x^2 and dG/dx, series for small x."""
    x = np.asarray(x, float)
    small = x < 0.02
    xs = np.where(small, x, 0.0)
    G = np.full_like(x, 1.5); dG = np.zeros_like(x)
    for m in range(3, 16):
        G = G - np.where(small, 2 * xs ** (m - 2) / (m * (m - 1) * (m - 2)), 0.0)
        dG = dG - np.where(small, 2 * xs ** (m - 3) / (m * (m - 1)), 0.0)
    xb = np.where(small, 0.5, x)
    L = np.log1p(-xb)
    g = xb + (1 - xb) ** 2 * L
    gp = xb - 2 * (1 - xb) * L
    G = np.where(small, G, g / xb ** 2)
    dG = np.where(small, dG, gp / xb ** 2 - 2 * g / xb ** 3)
    return G, dG


def phi(n0, n1, n2, n3, n1v, n2v):
    """White-Bear mark I free-energy density (units kT) and its partial derivatives."""
    one = 1 - n3
    L = np.log(one)
    G, dG = _G(n3)
    f3 = G / (36 * np.pi * one ** 2)
    df3 = (dG + 2 * G / one) / (36 * np.pi * one ** 2)
    A = n2 ** 3 - 3 * n2 * n2v ** 2
    P = -n0 * L + (n1 * n2 - n1v * n2v) / one + A * f3
    d0 = -L
    d1 = n2 / one
    d2 = n1 / one + 3 * (n2 ** 2 - n2v ** 2) * f3
    d3 = n0 / one + (n1 * n2 - n1v * n2v) / one ** 2 + A * df3
    d1v = -n2v / one
    d2v = -n1v / one - 6 * n2 * n2v * f3
    return P, (d0, d1, d2, d3, d1v, d2v)


def bulk_n(rb, R):
    return (np.sum(rb), np.sum(rb * R), np.sum(rb * 4 * np.pi * R ** 2),
            np.sum(rb * 4 / 3 * np.pi * R ** 3), 0.0, 0.0)


# ---------------------------------------------------------------- the planar system
class Wall:
    def __init__(self, dz=0.02, Z=100.0):
        self.R = R = M.sig / 2
        self.B = B = M.B
        self.dz = dz
        self.Z = Z
        Rmax = R.max()
        self.N = N = int(np.ceil((Z + 2 * Rmax) / dz)) + 1
        self.z = z = np.arange(N) * dz
        hw = int(np.ceil(Rmax / dz)) + 2
        self.nfft = nfft = 1 << int(np.ceil(np.log2(N + hw + 4)))
        # first accessible index of each class and the stretched first cell
        self.j0 = np.array([int(np.ceil(R[i] / dz - 1e-12)) for i in range(B)])
        self.inside = z <= Z + 1e-9
        self.acc = np.array([(np.arange(N) >= self.j0[i]) & self.inside for i in range(B)])
        self.q = np.full((B, N), dz)
        for i in range(B):
            self.q[i, :self.j0[i]] = 0.0
            self.q[i, self.j0[i]] = dz / 2 + (z[self.j0[i]] - R[i])
        # cell-averaged kernels, stored as rfft of w(u) laid out circularly (index u/dz mod nfft)
        W3 = np.empty((B, nfft // 2 + 1), complex); W2 = np.empty_like(W3); W2v = np.empty_like(W3)
        self.mom = np.zeros((B, 3))
        for i in range(B):
            Ri = R[i]
            m = int(np.ceil(Ri / dz)) + 1
            u = np.arange(-m, m + 1) * dz
            a = np.clip(u - dz / 2, -Ri, Ri); b = np.clip(u + dz / 2, -Ri, Ri)
            I3 = lambda t: np.pi * (Ri ** 2 * t - t ** 3 / 3)
            I2 = lambda t: 2 * np.pi * Ri * t
            I2v = lambda t: np.pi * t ** 2
            for arr, I, col in ((W3, I3, 0), (W2, I2, 1), (W2v, I2v, 2)):
                w = (I(b) - I(a)) / dz
                buf = np.zeros(nfft)
                buf[np.arange(-m, m + 1) % nfft] = w
                arr[i] = np.fft.rfft(buf)
                self.mom[i, col] = w.sum() * dz
        self.W3, self.W2, self.W2v = W3, W2, W2v
        self.c0 = 1 / (4 * np.pi * R ** 2)
        self.c1 = 1 / (4 * np.pi * R)
        self.nfev = 0

    def set_nu(self, nu):
        self.nu = nu
        self.rb = M.rho * nu / M.nu
        nb = bulk_n(self.rb, self.R)
        P, d = phi(*[np.array(v) for v in nb])
        R = self.R
        self.mu_ex = d[0] + d[1] * R + d[2] * 4 * np.pi * R ** 2 + d[3] * 4 / 3 * np.pi * R ** 3
        self.betaP_fmt = float(nb[0] - P + sum(a * b for a, b in zip(nb, d)))
        self.betaP = M.bmcsl_pressure(self.rb, M.sig)

    def density(self, x):
        """rho_i(z_j) (absolute) from the unknowns x = ln(rho/rho_b) at accessible points."""
        X = np.zeros((self.B, self.N))
        X[self.acc] = x
        rho = np.where(self.acc, np.exp(X), 0.0)
        rho[:, ~self.inside] = 1.0
        return rho * self.rb[:, None]

    def weighted(self, rho):
        F = np.fft.rfft(rho * self.q, self.nfft, axis=1)
        N = self.N
        ir = lambda s: np.fft.irfft(s, self.nfft)[:N]
        F2 = F * self.W2; F2v = F * self.W2v
        n3 = ir(np.sum(F * self.W3, 0))
        n2 = ir(F2.sum(0)); n1 = ir((F2 * self.c1[:, None]).sum(0)); n0 = ir((F2 * self.c0[:, None]).sum(0))
        n2v = ir(F2v.sum(0)); n1v = ir((F2v * self.c1[:, None]).sum(0))
        return n0, n1, n2, n3, n1v, n2v

    def c1field(self, d):
        """c_i(z_j) = dz sum_m sum_a d_a(z_m) W_a,i(z_m - z_j)  (minus the one-body direct correlation)."""
        nf = self.nfft
        D = [np.fft.rfft(v, nf) for v in d]
        S = (np.conj(self.W2) * (D[0][None] * self.c0[:, None] + D[1][None] * self.c1[:, None] + D[2][None])
             + np.conj(self.W3) * D[3][None]
             + np.conj(self.W2v) * (D[4][None] * self.c1[:, None] + D[5][None]))
        return self.dz * np.fft.irfft(S, nf, axis=1)[:, :self.N]

    def residual(self, x):
        """G(x) = mu_ex - c[rho(x)] - x at accessible points; None if n3 >= 1 somewhere."""
        self.nfev += 1
        rho = self.density(x)
        n = self.weighted(rho)
        n3max = n[3].max()
        if not np.all(np.isfinite(rho)) or n3max >= 1 - 1e-12:
            return None, n3max
        _, d = phi(*n)
        c = self.c1field(d)
        return (self.mu_ex[:, None] - c)[self.acc] - x, n3max

    def contact(self, x):
        """rho_i(R_i)/rho_b,i by linear extrapolation of ln rho from the first two accessible points."""
        X = np.zeros((self.B, self.N)); X[self.acc] = x
        out = np.empty(self.B)
        for i in range(self.B):
            j = self.j0[i]
            t = (self.R[i] - self.z[j]) / self.dz
            out[i] = np.exp(X[i, j] + t * (X[i, j + 1] - X[i, j]))
        return out


# ---------------------------------------------------------------- solvers
def gmres(Av, b, tol, m, maxrestart=3):
    """Restarted GMRES(m) for A y = b from y = 0; returns y, relative residual, matvecs."""
    n = b.size
    y = np.zeros(n)
    bn = np.linalg.norm(b)
    r = b.copy(); nmv = 0; rel = 1.0
    for _ in range(maxrestart):
        beta = np.linalg.norm(r)
        V = np.zeros((m + 1, n)); H = np.zeros((m + 1, m))
        V[0] = r / beta
        cs = np.zeros(m); sn = np.zeros(m); e = np.zeros(m + 1); e[0] = beta
        k = 0
        for k in range(m):
            w = Av(V[k]); nmv += 1
            for j in range(k + 1):                 # modified Gram-Schmidt, twice
                h = V[j] @ w; H[j, k] += h; w -= h * V[j]
            for j in range(k + 1):
                h = V[j] @ w; H[j, k] += h; w -= h * V[j]
            H[k + 1, k] = np.linalg.norm(w)
            if H[k + 1, k] > 0:
                V[k + 1] = w / H[k + 1, k]
            for j in range(k):                      # Givens rotations
                t = cs[j] * H[j, k] + sn[j] * H[j + 1, k]
                H[j + 1, k] = -sn[j] * H[j, k] + cs[j] * H[j + 1, k]
                H[j, k] = t
            d = np.hypot(H[k, k], H[k + 1, k])
            cs[k], sn[k] = H[k, k] / d, H[k + 1, k] / d
            H[k, k] = d; H[k + 1, k] = 0
            e[k + 1] = -sn[k] * e[k]; e[k] = cs[k] * e[k]
            rel = abs(e[k + 1]) / bn
            if rel < tol:
                break
        kk = k + 1
        yk = np.linalg.solve(np.triu(H[:kk, :kk]), e[:kk])
        y += V[:kk].T @ yk
        if rel < tol:
            break
        r = b - Av(y); nmv += 1
        rel = np.linalg.norm(r) / bn
        if rel < tol:
            break
    return y, rel, nmv


def anderson(S, x, iters=300, beta=0.02, mem=6, log=None):
    """Safeguarded Anderson mixing on x (restart when the residual grows or n3 >= 1)."""
    X, Gs = [], []
    g, _ = S.residual(x)
    best = (np.abs(g).max(), x.copy())
    for it in range(iters):
        err = np.abs(g).max()
        if log is not None and it % 50 == 0:
            log(f"    anderson {it} max|G| {err:.3e}")
        if err < best[0]:
            best = (err, x.copy())
        X.append(x.copy()); Gs.append(g.copy())
        if len(X) > mem:
            X.pop(0); Gs.pop(0)
        if len(X) > 1:
            dG = np.array([Gs[j + 1] - Gs[j] for j in range(len(Gs) - 1)]).T
            dX = np.array([X[j + 1] - X[j] for j in range(len(X) - 1)]).T
            gam = np.linalg.lstsq(dG, g, rcond=None)[0]
            xn = x + beta * g - (dX + beta * dG) @ gam
        else:
            xn = x + beta * g
        gn, _ = S.residual(xn)
        if gn is None or np.abs(gn).max() > 2 * err:   # safeguard: plain damped step, restart history
            X, Gs = [], []
            lam = beta
            while True:
                xn = x + lam * g
                gn, _ = S.residual(xn)
                if gn is not None:
                    break
                lam /= 2
        x, g = xn, gn
    err = np.abs(g).max()
    if err < best[0]:
        best = (err, x.copy())
    return best[1]


def newton(S, x, tol=1e-6, maxit=60, m=80, log=print):
    g, n3 = S.residual(x)
    if g is None:
        raise RuntimeError("initial guess has n3 >= 1")
    hist = []
    eta = 1e-2
    for it in range(maxit):
        err = np.abs(g).max(); gn = np.linalg.norm(g)
        hist.append(err)
        log(f"    newton {it} max|G| {err:.3e} |G|_2 {gn:.3e} n3max {n3:.4f} nfev {S.nfev}")
        if err < tol:
            return x, hist, True
        def Av(v):
            vn = np.abs(v).max()
            eps = 1e-7 / max(vn, 1e-30)
            gv, _ = S.residual(x + eps * v)
            if gv is None:
                gv2, _ = S.residual(x - eps * v)
                return (g - gv2) / eps
            return (gv - g) / eps
        d, rel, nmv = gmres(Av, -g, eta, m)
        lam = 1.0
        while lam > 1e-4:
            xn = x + lam * d
            gnew, n3n = S.residual(xn)
            if gnew is not None and np.linalg.norm(gnew) < (1 - 1e-4 * lam) * gn:
                break
            lam /= 2
        else:
            log("    line search failed")
            return x, hist, False
        log(f"      gmres rel {rel:.2e} in {nmv} matvecs, step {lam}")
        # Eisenstat-Walker (choice 2) forcing term
        ratio = np.linalg.norm(gnew) / gn
        eta = min(0.1, max(0.9 * ratio ** 2, 1e-6, 0.5 * tol / max(np.linalg.norm(gnew), 1e-30)))
        x, g, n3 = xn, gnew, n3n
    return x, hist, False


# ---------------------------------------------------------------- driver
def report(S, x, nu, out, log=print):
    rho = S.density(x)
    cv = S.contact(x)
    s = float(np.sum(cv * S.rb))
    log(f"  contact theorem: sum rho_i(R_i) = {s:.6f}, beta P BMCSL = {S.betaP:.6f} "
        f"(FMT bulk {S.betaP_fmt:.6f}); ratio {s / S.betaP:.5f}")
    groups = [(1, 1.5), (1.5, 2.5), (2.5, 4), (4, 6), (6, 10.01)]
    for lo, hi in groups:
        c = [i for i in range(S.B) if lo <= S.R[i] < hi]
        w = M.P[c] / M.P[c].sum()
        log(f"  radii {lo}-{hi}: contact value FMT {np.sum(w * cv[c]):.2f}")
    rel = rho / S.rb[:, None]
    gam = [float(np.sum(np.where(np.arange(S.N) >= S.j0[i], rel[i], 0.0)[S.inside] * S.q[i][S.inside])
                 - S.z[S.inside][-1] - S.dz / 2) for i in range(S.B)]
    log("  Gamma_i (FMT): " + " ".join(f"sig {M.sig[i]:.2f}: {gam[i]:.4f}" for i in (0, 15, 29)))
    tail = np.abs(rel[:, (S.z > S.Z - 10) & S.inside] - 1).max()
    log(f"  max |rho/rho_b - 1| over the last 10 before Z: {tail:.2e}")
    if out:
        np.save(f"{out}/fmt_profile_{nu:g}{'' if abs(S.dz - 0.02) < 1e-12 else f'_dz{S.dz:g}'}.npy",
                np.vstack([S.z, rel]))
    return cv, gam


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--dz', type=float, default=0.02)
    ap.add_argument('--Z', type=float, default=100.0)
    ap.add_argument('--nus', default='0.4,0.5,0.6')
    ap.add_argument('--out', default='.')
    ap.add_argument('--tol', type=float, default=1e-6)
    a = ap.parse_args()
    log = lambda s: print(s, flush=True)
    S = Wall(a.dz, a.Z)
    log(f"grid dz {a.dz} Z {a.Z}: {S.N} points, nfft {S.nfft}, {int(S.acc.sum())} unknowns")
    targets = sorted(float(t) for t in a.nus.split(','))
    steps = list(np.round(np.arange(0.1, 0.3, 0.1), 6)) + list(np.round(np.arange(0.3, targets[-1] + 1e-9, 0.02), 6))
    steps = sorted(set(steps) | set(targets))
    x = np.zeros(int(S.acc.sum()))
    prev = None
    for nu in steps:
        S.set_nu(nu)
        t0 = time.time(); f0 = S.nfev
        if prev is not None and prev[0][0] > 0:       # secant predictor in nu
            (nu1, x1), (nu2, x2) = prev
            xp = x2 + (x2 - x1) * (nu - nu2) / (nu2 - nu1)
            gp, _ = S.residual(xp)
            g0, _ = S.residual(x)
            if gp is not None and np.linalg.norm(gp) < np.linalg.norm(g0):
                x = xp
        x = anderson(S, x, iters=30, beta=0.02, log=None)
        x, hist, ok = newton(S, x, tol=a.tol, log=log)
        dt = time.time() - t0
        log(f"nu {nu}: converged {ok}, {len(hist) - 1} Newton steps, {S.nfev - f0} residual evaluations, "
            f"{dt:.1f} s, final max|G| {hist[-1]:.2e}")
        if not ok:
            log("  residual history: " + " ".join(f"{h:.2e}" for h in hist))
            break
        prev = ((prev[1] if prev else (nu - 1.0, x.copy())), (nu, x.copy()))
        if any(abs(nu - t) < 1e-9 for t in targets):
            report(S, x, nu, a.out, log)


if __name__ == '__main__':
    main()
