"""Independent kinematic chain of the cradle machine for tests (written from docs/conventions.md, with an explicit
hand sign instead of mirroring), complex-step friendly."""

import numpy as np


def rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0 * c], [s, c, 0 * c], [0 * c, 0 * c, 1 + 0 * c]])


def chain(u, theta, psi, cutter, settings, hand_sign):
    """Member-frame point and cutter normal n_h for scalar (u, theta, psi); hand_sign = +1 RH, -1 LH."""
    h = -hand_sign                                   # +1 on the left-hand machine
    s, a_h, R, rf = cutter.sign, cutter.blade_angle, cutter.point_radius, cutter.edge_radius
    u0, uj = cutter.fillet_range
    if u >= uj:                                      # seed 001 Eq. (7), (9)
        rho, z = R + s * u * np.sin(a_h), -u * np.cos(a_h)
        nr, nz = np.cos(a_h), s * np.sin(a_h)
    else:                                            # Eq. (8), (10)
        lam = (np.pi / 2 - a_h) - (uj - u) / rf
        T = R - s * rf * (1 - np.sin(a_h)) / np.cos(a_h)
        rho, z = T + s * rf * np.sin(lam), -rf * (1 - np.cos(lam))
        nr, nz = np.sin(lam), s * np.cos(lam)
    S, q, g = settings.radial_setting, settings.cradle_angle, settings.machine_root_angle
    m = settings.ratio_of_roll
    coef = list(settings.modified_roll) + [0.0] * (4 - len(settings.modified_roll))
    psi_i = m * (psi - coef[0] * psi**2 / 2 - coef[1] * psi**3 / 6 - coef[2] * psi**4 / 24 - coef[3] * psi**5 / 120)
    E = settings.blank_offset + sum(c * psi ** (k + 1) for k, c in enumerate(settings.blank_offset_poly))
    # cradle turns by h*psi; the cutter centre at psi = 0 is S(-cos q, h sin q, 0); cutter angle measured from O->C
    d0 = np.array([-S * np.cos(q), h * S * np.sin(q), 0.0])
    base = np.arctan2(d0[1], d0[0])
    e = np.array([np.cos(base + h * theta), np.sin(base + h * theta), 0 * theta])
    r_c = d0 + rho * e + np.array([0, 0, 1.0]) * z
    n_c = nr * e + np.array([0, 0, 1.0]) * nz
    Rc = rz(h * psi)
    r_m, n_m = Rc @ r_c, Rc @ n_c
    a = np.array([-np.cos(g), 0.0, np.sin(g)])
    A = np.array([0.0, -h * E, -settings.sliding_base])      # offset away from the cutter-centre side
    B = np.array([[np.sin(g), 0, np.cos(g)], [0, 1, 0], a])  # rows: member basis at psi_i = 0
    Rw = rz(-h * psi_i)
    return Rw @ (B @ (r_m - A - settings.machine_centre_to_back * a)), Rw @ (B @ n_m)
