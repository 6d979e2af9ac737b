"""The Fig. 12 alpha = -3, omega = 10, nu = 0.6 mixture in 30 geometric classes,
and the wall as a Percus-Yevick component, for wall_product.py,
wall_mediators.py and wall_contact.py (docs/MODEL.md section 8, walls)."""
import numpy as np
from excluded_pins import hhat
import walled_pins as W  # the wall's contact step and contact values, shared

alpha, omega, nu = -3.0, 10.0, 0.6
s1 = 3.6467469369631162                 # level-1 cell size at N = 3e4
B = 30
edges = np.geomspace(1, omega, B + 1)


def moment(p, a, b):
    e = alpha + p + 1
    return (b ** e - a ** e) / e if abs(e) > 1e-12 else np.log(b / a)


P = np.array([moment(0, edges[i], edges[i + 1]) for i in range(B)])
sig = 2 * (np.array([moment(3, edges[i], edges[i + 1]) for i in range(B)]) / P) ** (1 / 3)
P /= P.sum()
rho = nu / (np.pi / 6 * np.sum(P * sig ** 3)) * P
sw = W.WALL_DIAMETER * sig.max()         # the wall: a sphere 20 largest diameters wide, negligible density
rho_w = np.append(rho, W.WALL_PACKING * 6 / (np.pi * sw ** 3))
sig_w = np.append(sig, sw)
dk = 0.25 * np.pi / (sw / 2 + W.WALL_REACH * sig.max())
k = np.arange(1, int(30 / sig.min() / dk)) * dk


def bmcsl_pressure(rho_classes, sigma):
    """beta P of the Boublik-Mansoori-Carnahan-Starling-Leland equation of state."""
    xi = [np.pi / 6 * np.sum(rho_classes * sigma ** m) for m in range(4)]
    e = 1 - xi[3]
    return 6 / np.pi * (xi[0] / e + 3 * xi[1] * xi[2] / e ** 2 + (3 - xi[3]) * xi[2] ** 3 / e ** 3)


def radial(Y, r):
    """h(r) from Y(k) = hhat(k) by the sine transform on the grid k."""
    return (np.sin(np.outer(r, k)) @ (k * Y)) * dk / (2 * np.pi ** 2 * r)


def contact_step(c, g, r):
    """The step of h_cW at contact, -1 inside and (g - 1) e^{-(r - R)/r_min} outside
    (R = (sig_c + sw)/2, g the PY contact value), at distances r."""
    return W.contact_step((sig[c] + sw) / 2, g, sig.min() / 2, r)


def contact_step_hat(c, g, q):
    """Its 3D Fourier transform, in closed form, at wave numbers q."""
    return W.contact_step_hat((sig[c] + sw) / 2, g, sig.min() / 2, q)


def wall_hhat(rho_classes):
    """PY's wall correlations hhat_cW for every class c, the classes at densities rho_classes:
    (the smooth rest on the grid k, columns c; the contact values g_c). The step at contact
    is transformed in closed form and added back in r (a truncated transform would smear it)."""
    rw = np.append(rho_classes, rho_w[-1])
    Y = np.empty((len(k), B))
    for i0 in range(0, len(k), 500):
        Y[i0:i0 + 500] = hhat(k[i0:i0 + 500], rw, sig_w)[:, :B, B]
    g = W.wall_contact_values(rho_classes, sig, sw)
    for c in range(B):
        Y[:, c] -= contact_step_hat(c, g[c], k)
    return Y, g


def wall_profile(W, c, z):
    """Class c's density at centre height z above the wall over its bulk density (0 where it
    does not fit); W = wall_hhat(...)."""
    Y, g = W
    r = sw / 2 + z
    return np.where(z < sig[c] / 2, 0.0, 1 + radial(Y[:, c], r) + contact_step(c, g[c], r))
