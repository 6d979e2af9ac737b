#!/usr/bin/env python3
"""Python's ContactList against the same loop through the C++ API, on the
same arrays: N particles (3D, periodic, radii r^-3 on [1, 5], nu = 0.4,
random centres), moving x0 + t v (|v| ~ 0.01 per step); each step
update(positions, radii) then pairs(). Prints the fastest of --reps runs'
seconds per step of each, alternated, and their ratio.

    PYTHONPATH=build/python python3 bench/python_overhead.py --hgrid-build build
"""
import argparse
import os
import subprocess
import tempfile
import time

import numpy as np

import hgridlab


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--hgrid-build", default="build")
    ap.add_argument("--n", type=int, default=100000)
    ap.add_argument("--steps", type=int, default=100)
    ap.add_argument("--skin", type=float, default=0.4)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--seed", type=int, default=7)
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    u = rng.random(a.n)
    radii = (1.0 + u * (5.0**-2 - 1.0)) ** (-1.0 / 2)
    side = (np.sum(4 / 3 * np.pi * radii**3) / 0.4) ** (1 / 3)
    box = np.full(3, side)
    x0 = rng.random((a.n, 3)) * side
    v = rng.normal(0.0, 0.01, (a.n, 3))
    print(f"seed {a.seed}, N = {a.n}, {a.steps} steps, skin {a.skin}", flush=True)
    with tempfile.TemporaryDirectory() as d:
        for name, arr in (("x0", x0), ("v", v), ("r", radii), ("box", box)):
            np.ascontiguousarray(arr, dtype=np.float64).tofile(os.path.join(d, name + ".bin"))
        best_py, best_cpp = float("inf"), float("inf")
        for _ in range(a.reps):
            cl = hgridlab.ContactList(box, periodic=(True, True, True), skin=a.skin)
            seconds = 0.0
            for t in range(a.steps):
                x = x0 + t * v
                t1 = time.perf_counter()
                cl.update(x, radii)
                cl.pairs()
                seconds += time.perf_counter() - t1
            best_py = min(best_py, seconds / a.steps)
            out = subprocess.run([os.path.join(a.hgrid_build, "contact_list_replay"), d, "3", str(a.n),
                                  str(a.steps), str(a.skin), "1"], check=True, capture_output=True, text=True)
            best_cpp = min(best_cpp, float(out.stdout))
    print(f"python {best_py * 1e3:.3f} ms/step, C++ {best_cpp * 1e3:.3f} ms/step, ratio {best_py / best_cpp:.3f}")


if __name__ == "__main__":
    main()
