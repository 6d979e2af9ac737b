"""A soft-sphere gas stepped with velocity Verlet in numpy, its contacts from
hgridlab.ContactList kept between the steps (periodic in x and y, walled in z).

    PYTHONPATH=build/python python3 examples/contact_list_steps.py
"""
import numpy as np

import hgridlab

rng = np.random.default_rng(1)  # the seed: the same run every time
per_axis, side, dt, stiffness = 16, 60.0, 0.01, 100.0
n = per_axis**3  # a 16^3 lattice of sites 3.75 apart: no overlap at the start
box = np.full(3, side)
radii = 0.5 + rng.random(n)
site = np.stack(np.unravel_index(np.arange(n), (per_axis,) * 3), axis=1)
x = (site + 0.5) * side / per_axis
v = rng.normal(0.0, 0.5, (n, 3))

# [readme]
cl = hgridlab.ContactList(box, periodic=(True, True, False), skin=0.5)  # or skin="auto"


def forces(x):
    cl.update(x, radii)                   # rebuilds only when a particle may have crossed its skin
    i, j = cl.pairs().T.astype(np.intp)   # every touching pair, i < j, ascending
# [/readme]
    d = x[j] - x[i]
    d[:, :2] -= side * np.round(d[:, :2] / side)  # minimum image on the periodic axes
    dist = np.linalg.norm(d, axis=1)
    push = (stiffness * (radii[i] + radii[j] - dist) / dist)[:, None] * d
    f = np.zeros_like(x)
    np.add.at(f, i, -push)
    np.add.at(f, j, push)
    return f


f = forces(x)
for step in range(300):
    v += 0.5 * dt * f
    x += dt * v
    bounce = ((x[:, 2] < radii) & (v[:, 2] < 0)) | ((x[:, 2] > side - radii) & (v[:, 2] > 0))
    v[bounce, 2] *= -1  # hard walls at z = 0 and z = side: the centres bounce off
    f = forces(x)
    v += 0.5 * dt * f
s = cl.stats
print(f"{s['steps']} steps, {s['builds']} list builds, {s['contacts']} contacts now")
assert s["builds"] < s["steps"]
