"""Contact forces of an LTCA as vertex loads of the FE tooth model: :func:`contact_load_cases`.

Each normal contact force acts at the foot of its point on the loaded flank grid, shared among the four vertices of
the grid cell with the bilinear weights of the LTCA compliance, pointing into the tooth; the load cases follow the
middle tooth of the segment through its engagement (:mod:`.fe_root_stress`).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import DesignError

__all__ = ["contact_load_cases", "locate"]


def _outward_normals(grid, other):
    """Unit normals of a flank grid pointing out of the tooth (away from the other flank of the same tooth)."""
    from ..meshing.ltca.mesher import grid_normals

    n = grid_normals(grid)
    s = np.sign(np.einsum("...i,...i->...", n, grid - other))
    s[s == 0] = 1.0
    return n * s[..., None]


def _rot(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def contact_load_cases(mesh, side, points, pair_of_point, force, teeth_of_pairs, tol=0.5):
    """Vertex forces of the load cases that follow tooth 0 through its engagement.

    Parameters
    ----------
    mesh : SegmentMesh
        Segment of the member (teeth ``mesh.teeth``, tooth t at t pitch angles from the reference tooth).
    side : str
        Loaded flank.
    points : list of (n_i, 3) float, mm
        Contact points of each mesh position on the reference tooth (member frame of the grids).
    pair_of_point : list of (n_i,) int
        Pair index of every point.
    force : list of (n_i,) float, N
        Normal contact force of every point (>= 0).
    teeth_of_pairs : (n_pairs,) int
        Segment tooth of each pair (pinion: k, gear: -k for pair k of the TCA).
    tol : float, mm
        Largest distance from the flank grid of the most loaded point of each pair (catches frame or side mix-ups,
        which put the points millimetres away). The LTCA's potential contact points lie in the tangent plane of each
        contact, off the curved flank by about s^2 k / 2 at a distance s from the contact point (over a millimetre at
        the ends of a long contact): each force acts at the foot of its point on the flank grid, as in the LTCA
        compliance.

    Returns
    -------
    forces : (n_cases, nv, 3) float, N
    cases : list of (int, int)
        (mesh position, pair j in the role of tooth 0) of every case.
    """
    teeth = list(mesh.teeth)
    other = "concave" if side == "convex" else "convex"
    pitch = mesh.pitch_angle
    nodes0 = mesh.flank_nodes[(0, side)]
    grid0 = mesh.vertices[nodes0]
    nout0 = _outward_normals(grid0, mesh.vertices[mesh.flank_nodes[(0, other)]])
    tp = np.asarray(teeth_of_pairs, int)
    forces, cases = [], []
    for m, (P, pr, f) in enumerate(zip(points, pair_of_point, force)):
        P, pr, f = np.asarray(P, float).reshape(-1, 3), np.asarray(pr, int), np.asarray(f, float)
        live = f > 0
        if not live.any():
            continue
        P, pr, f = P[live], pr[live], f[live]
        P = _on_reference_tooth(grid0, P, pr, f, pitch, side, tol)
        i, j, xi, eta, _ = locate(grid0, P)
        # force on the reference tooth, bilinear shares on the four cell vertices, into the tooth
        parts = []
        for di, dj, wgt in ((0, 0, (1 - xi) * (1 - eta)), (1, 0, xi * (1 - eta)), (0, 1, (1 - xi) * eta),
                            (1, 1, xi * eta)):
            parts.append((nodes0[i + di, j + dj], -(wgt * f)[:, None] * nout0[i + di, j + dj]))
        for j0 in np.unique(pr):
            F = np.zeros((len(mesh.vertices), 3))
            for jp in np.unique(pr):
                t = int(tp[jp] - tp[j0])
                if t not in teeth:
                    continue
                sel = pr == jp
                # tooth t is the reference tooth turned by t pitches (vertex of tooth 0 -> same vertex of tooth t)
                R = _rot(t * pitch)
                nodes_t = mesh.flank_nodes[(t, side)]
                for v0, Fv in parts:
                    vt = _map_nodes(nodes0, nodes_t, v0[sel])
                    np.add.at(F, vt, Fv[sel] @ R.T)
            forces.append(F)
            cases.append((m, int(j0)))
    if not forces:
        raise DesignError.single("ltca force", 0, "> 0 at some mesh position", "N", "FE root stress")
    return np.stack(forces), cases


def _bilinear(grid, i, j, xi, eta):
    x, e = np.asarray(xi)[..., None], np.asarray(eta)[..., None]
    return ((1 - x) * (1 - e) * grid[i, j] + x * (1 - e) * grid[i + 1, j] + (1 - x) * e * grid[i, j + 1]
            + x * e * grid[i + 1, j + 1])


def locate(grid, P, retry=0.05):
    """Cell (i, j) and bilinear coordinates (xi, eta) of the foot of points on a flank grid, and the distance (mm).

    :func:`~spiralbevel.meshing.ltca.locate.locate_on_grid` (Gauss-Newton) first; a point whose foot is more than
    ``retry`` mm away (a Gauss-Newton step that did not converge) is located again by a search over a 41 x 41 lattice
    of bilinear coordinates in the four cells around its nearest grid vertex (the foot to 1/40 of a cell).
    """
    from ..meshing.ltca.locate import locate_on_grid

    i, j, xi, eta, _ = locate_on_grid(grid, P)
    d = np.linalg.norm(_bilinear(grid, i, j, xi, eta) - P, axis=1)
    n0, n1 = grid.shape[0] - 1, grid.shape[1] - 1
    t = np.linspace(0.0, 1.0, 41)
    XI, ETA = np.meshgrid(t, t, indexing="ij")
    for q in np.flatnonzero(d > retry):
        a, b = np.unravel_index(int(np.argmin(np.linalg.norm(grid - P[q], axis=-1))), grid.shape[:2])
        for ci in range(max(0, a - 1), min(n0, a + 1)):
            for cj in range(max(0, b - 1), min(n1, b + 1)):
                dd = np.linalg.norm(_bilinear(grid, ci, cj, XI, ETA) - P[q], axis=-1)
                k = np.unravel_index(int(np.argmin(dd)), dd.shape)
                if dd[k] < d[q]:
                    i[q], j[q], xi[q], eta[q], d[q] = ci, cj, XI[k], ETA[k], dd[k]
    return i, j, xi, eta, d


def _foot_distance(grid, P):
    return locate(grid, P)[4]


def _on_reference_tooth(grid0, P, pr, f, pitch, side, tol):
    """The points of every pair turned by the whole number of pitches that puts the pair's most loaded point (the
    nearest to its contact centre, on the flank to within the tangent plane's sag) on the reference tooth's flank (the
    LTCA result gives them on the reference tooth; this also accepts points left on another tooth)."""
    out = P.copy()
    for jp in np.unique(pr):
        sel = pr == jp
        top = P[sel][np.argmax(f[sel])][None]
        best = (np.inf, 0)
        for t in range(-3, 4):
            d = float(_foot_distance(grid0, top @ _rot(-t * pitch).T)[0])
            best = min(best, (d, t))
        if best[0] > tol:
            raise DesignError.single("ltca points", f"{best[0]:.3f} mm from the {side} flank grid", f"<= {tol} mm",
                                     "mm", "FE root stress: the LTCA contact points must lie on the loaded flank of "
                                     "the FE tooth model (same member frame)")
        out[sel] = P[sel] @ _rot(-best[1] * pitch).T
    return out


def _map_nodes(nodes0, nodes_t, v):
    """Vertices of tooth t at the grid places of the tooth-0 vertices ``v``."""
    order = np.argsort(nodes0.ravel())
    return nodes_t.ravel()[order[np.searchsorted(nodes0.ravel()[order], v)]]
