"""Sections of flank grids: the intersection with a sphere about the apex, and the tooth profile it gives."""

from __future__ import annotations

import numpy as np


def sphere_section(points, radius):
    """Points where the toe -> heel rows of a flank grid cross the sphere |r| = radius (one per grid column).

    Parameters
    ----------
    points : (n, m, 3) float, mm
        Flank grid, toe -> heel along axis 0.
    radius : float, mm

    Returns
    -------
    (k, 3) float, mm
        Linear interpolation between the two rows that bracket the sphere; columns that do not cross are skipped.
    """
    points = np.asarray(points, float)
    r = np.linalg.norm(points, axis=-1) - radius
    out = []
    for j in range(points.shape[1]):
        g = r[:, j]
        k = np.nonzero(np.diff(np.sign(g)))[0]
        if k.size:
            i = k[0]
            t = g[i] / (g[i] - g[i + 1])
            out.append(points[i, j] + t * (points[i + 1, j] - points[i, j]))
    return np.array(out).reshape(-1, 3)


def tooth_profile(convex, concave, radius):
    """Both flank profiles of one tooth on the sphere |r| = radius, as (arc from the tooth centre, radius) pairs.

    Parameters
    ----------
    convex, concave : (n, m, 3) float, mm
        Point grids of the two flanks of one tooth (member frame).
    radius : float, mm

    Returns
    -------
    list of (k, 2) float, mm, or None
        Convex then concave profile: arc length along the circle of the point's radius, measured from the mean
        azimuth of both profiles, and the radius from the axis. None when a flank does not reach the sphere.
    """
    pts = [sphere_section(g, radius) for g in (convex, concave)]
    if any(len(p) < 2 for p in pts):
        return None
    allp = np.concatenate(pts)
    az0 = float(np.angle(np.mean(np.exp(1j * np.arctan2(allp[:, 1], allp[:, 0])))))
    out = []
    for p in pts:
        az = np.angle(np.exp(1j * (np.arctan2(p[:, 1], p[:, 0]) - az0)))
        rr = np.hypot(p[:, 0], p[:, 1])
        out.append(np.stack([az * rr, rr], -1))
    return out
