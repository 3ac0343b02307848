"""Brute-force oracle of the first touch of two real flanks: the angular gap about the gear axis, maximised over the
common part of the two flanks' axial projections.

Rotating about the gear axis maps every point to (z, rho, theta): axial position and radius, which a gear rotation
keeps, and the angle, which it shifts by the rotation. Seen from the gear axis, each real flank (the pinion's at its
rotation phi1 and the gear's at rotation 0) is then a function theta(z, rho) on a region of the (z, rho) half-plane,
its axial projection (a tooth flank is crossed once by the circles about the gear axis that meet it). The gear turned
by phi2 holds a point of the pinion flank exactly where theta_p(z, rho) - theta_g(z, rho) = phi2: two real flanks
touch at the gear rotation phi2 wherever their projections overlap, and the gear turned back onto the pinion first
touches at the extremum of this angular gap over the overlap -- an interior extremum (a surface contact), a point of
one flank's boundary (an edge contact) or where the two boundaries cross (a corner) alike.

The oracle finds that extremum by brute force: each flank is sampled on a dense grid of its parameters, with its
boundary found by bisection of ``contains`` between grid neighbours; every sample's (z, rho) is looked up on the other
flank (a 2 x 2 Newton solve of the other flank's (z, rho) from the nearest sample, forward-difference Jacobian) and
counts where the point found lies on the other real flank. The best samples of distinct parts of the overlap are then
refined by zooming windows in the (z, rho) plane (a 9 x 9 grid, factor 4 per level; the boundary of the overlap
bisected between grid neighbours of which one is in it and one is not). It uses only the surfaces' ``evaluate`` and
``contains`` and the assembly axes ``(a1, o1, a2, o2, B2)`` (pinion: rotation about +z through o1; gear member frame
-> fixed by rot(a2, phi2) @ B2): no normals, no contact equations, none of the library's contact code.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree


def _rz(a):
    c, s = np.cos(a), np.sin(a)
    R = np.zeros(np.shape(a) + (3, 3))
    R[..., 0, 0], R[..., 0, 1], R[..., 1, 0], R[..., 1, 1], R[..., 2, 2] = c, -s, s, c, 1.0
    return R


def flank_box(surface, reach=1.0, n=161, pad=0.05):
    """Parameter box (2, 2) of a surface's real flank: the extent of the points of an n x n grid over
    ``reference_params +- reach`` inside its boundaries (``boundary_margins``), widened by ``pad`` of the extent on
    each side."""
    ref = np.asarray(surface.reference_params, float)
    t = np.linspace(-reach, reach, n)
    q = ref + np.stack(np.meshgrid(t, t, indexing="ij"), -1).reshape(-1, 2)
    with np.errstate(all="ignore"):
        q = q[np.all(np.asarray(surface.boundary_margins(q)) >= 0, axis=-1)]
    lo, hi = q.min(0), q.max(0)
    if np.any(np.isclose(lo, ref - reach)) or np.any(np.isclose(hi, ref + reach)):
        raise ValueError("the real flank reaches the border of the scanned box: increase reach")
    d = pad * (hi - lo)
    return np.stack([lo - d, hi + d], 1)


class GapOracle:
    """First touch of two real flanks by the angular gap about the gear axis (see the module docstring).

    Parameters
    ----------
    pinion, gear : surfaces with ``evaluate(params) -> (points, normals)`` and ``contains(params)`` (member frames)
    box1, box2 : (2, 2) float
        Parameter boxes that hold each real flank (:func:`flank_box`).
    axes : tuple
        ``(a1, o1, a2, o2, B2)`` of the assembly.
    n : (int, int)
        Grid of each flank's box.
    k : int
        Nearest grid samples from which a (z, rho) is looked up on a flank (each sheet of a folded flank).
    """

    def __init__(self, pinion, gear, box1, box2, axes, n=(90, 45), k=8):
        self.s = (pinion, gear)
        self.box = (np.asarray(box1, float), np.asarray(box2, float))
        self.o1, self.a2, self.o2, self.B2 = (np.asarray(axes[i], float) for i in (1, 2, 3, 4))
        e1 = np.cross(self.a2, [0.0, 1.0, 0.0])
        if np.linalg.norm(e1) < 0.1:
            e1 = np.cross(self.a2, [1.0, 0.0, 0.0])
        self.e1 = e1 / np.linalg.norm(e1)
        self.e2 = np.cross(self.a2, self.e1)
        self.n, self.k = n, k
        self.grid = [self._grid(m) for m in (0, 1)]
        self._sides = (self._side(0), self._side(1))

    # ------------------------------------------------------------ maps
    def _cyl(self, p):
        """(z, rho, theta) (k, 3) of fixed-frame points p (k, 3) about the gear axis."""
        v = p - self.o2
        x, y = v @ self.e1, v @ self.e2
        return np.stack([v @ self.a2, np.hypot(x, y), np.arctan2(y, x)], -1)

    def _map(self, m, q, phi1):
        """(z, rho, theta) of member m's flank points at params q (k, 2): the pinion at rotation phi1 (k,), the gear
        at rotation 0."""
        with np.errstate(all="ignore"):
            r = self.s[m].evaluate(q)[0]
        if m == 0:
            p = self.o1 + np.einsum("kij,kj->ki", _rz(phi1), r)
        else:
            p = self.o2 + r @ self.B2.T
        return self._cyl(p)

    def _grid(self, m):
        """Grid params (N, 2) of member m's box."""
        lo, hi = self.box[m][:, 0], self.box[m][:, 1]
        t = [np.linspace(lo[i], hi[i], self.n[i]) for i in (0, 1)]
        return np.stack(np.meshgrid(*t, indexing="ij"), -1)

    def _lookup(self, m, phi1):
        """KD-tree over (z, rho) of member m's grid (at pinion rotation phi1) and the grid's params."""
        q = self.grid[m].reshape(-1, 2)
        zrt = self._map(m, q, np.full(len(q), phi1))
        fin = np.all(np.isfinite(zrt), axis=1)
        return cKDTree(zrt[fin, :2]), q[fin]

    def _invert(self, m, zr, phi1, q0, iters=30):
        """Params q (k, 2) of member m's flank with (z, rho) = zr (k, 2), its theta (k,) and whether the solve
        converged (2 x 2 Newton, forward differences, steps limited; a solve whose residual stops falling is
        dropped)."""
        q = np.array(q0, float)
        h = 1e-7
        act = np.arange(len(q))
        res = np.full(len(q), np.inf)
        for _ in range(iters):
            if not act.size:
                break
            qa = q[act]
            ph = np.full(act.size, phi1)
            f0 = self._map(m, qa, ph)[:, :2]
            r = f0 - zr[act]
            ra = np.max(np.abs(r), axis=1)
            keep = np.isfinite(ra) & (ra > 1e-11) & ~(ra > 0.5 * res[act])
            res[act] = ra
            act, qa, f0, r = act[keep], qa[keep], f0[keep], r[keep]
            if not act.size:
                break
            ph = ph[keep]
            J = np.stack([(self._map(m, qa + h * np.eye(2)[j], ph)[:, :2] - f0) / h for j in (0, 1)], -1)
            good = np.all(np.isfinite(J), axis=(1, 2))
            good &= np.abs(np.linalg.det(np.where(good[:, None, None], J, np.eye(2)))) > 1e-300
            dq = np.linalg.solve(np.where(good[:, None, None], J, np.eye(2)),
                                 np.where(good[:, None], -r, 0.0)[..., None])[..., 0]
            q[act] = qa + np.clip(dq, -0.05, 0.05)
            act = act[good]
        f = self._map(m, q, np.full(len(q), phi1))
        ok = np.all(np.abs(f[:, :2] - zr) < 1e-10, axis=1)
        return q, f[:, 2], ok

    def _on_flank(self, m, q):
        """Member m's params q (k, 2) inside its boundaries (toe, heel, top, fillet junction: ``boundary_margins``
        >= -1e-9 where the surface has them, else ``contains``); whether a sheet is cut away is decided by depth."""
        s = self.s[m]
        with np.errstate(all="ignore"):
            if hasattr(s, "boundary_margins"):
                return np.all(np.asarray(s.boundary_margins(q)) >= -1e-9, axis=-1)
            return np.asarray(s.contains(q), bool)

    def _side(self, m):
        """+1 where turning a point of member m's flank about the gear axis in +theta leaves the tooth (along the
        outward normal), -1 where it enters it: the sign of n . (a2 x v) at the reference point."""
        q = np.asarray(self.s[m].reference_params, float)[None]
        r, n = self.s[m].evaluate(q)
        if m == 0:
            p, nf = self.o1 + r[0], n[0]
        else:
            p, nf = self.o2 + self.B2 @ r[0], self.B2 @ n[0]
        return float(np.sign(nf @ np.cross(self.a2, p - self.o2)))

    def _theta(self, m, zr, phi1, tree, qg):
        """Angle theta (k,) of member m's real flank at (z, rho) = zr (k, 2), NaN where none: solved from each of the
        ``self.k`` nearest grid samples; where the flank covers (z, rho) twice (an envelope past its limit line,
        folded back over itself) the sheet deepest in the tooth bounds the material, the other is cut away."""
        _, kk = tree.query(zr, k=self.k)
        j = len(zr)
        q, t, ok = self._invert(m, np.repeat(zr, self.k, axis=0), phi1, qg[kk.reshape(-1)])
        ok &= self._on_flank(m, q)
        side = self._sides[m]
        depth = np.where(ok, -side * t, -np.inf).reshape(j, self.k)   # deepest sheet: largest -side theta
        c = np.argmax(depth, axis=1)
        return np.where(np.isfinite(depth[np.arange(j), c]), t.reshape(j, self.k)[np.arange(j), c], np.nan)

    def _gap(self, zr, phi1, trees, ref):
        """Angular gap phi2 = theta_p - theta_g (k,) at (z, rho) = zr (k, 2) (the 2 pi turn nearest ``ref``), NaN
        where a flank's point there is not on its real flank."""
        th = [self._theta(m, zr, phi1, *trees[m]) for m in (0, 1)]
        d = th[0] - th[1]
        d = d - 2 * np.pi * np.round((d - ref) / (2 * np.pi))
        return d

    # ------------------------------------------------------------ samples
    def _flank_samples(self, m, bisections=40):
        """Member m's real-flank params: grid points inside and the boundary between grid neighbours (bisection)."""
        q = self.grid[m]
        inside = self._on_flank(m, q)
        out = [q[inside]]
        for ax in (0, 1):
            a = q[:-1] if ax == 0 else q[:, :-1]
            b = q[1:] if ax == 0 else q[:, 1:]
            ia = inside[:-1] if ax == 0 else inside[:, :-1]
            ib = inside[1:] if ax == 0 else inside[:, 1:]
            f = ia != ib
            pin = np.where(ia[f][:, None], a[f], b[f])
            pout = np.where(ia[f][:, None], b[f], a[f])
            for _ in range(bisections):
                mid = 0.5 * (pin + pout)
                c = self._on_flank(m, mid)
                pin, pout = np.where(c[:, None], mid, pin), np.where(c[:, None], pout, mid)
            out.append(pin)
        return np.concatenate(out)

    def _window(self, zr0, w, phi1, trees, ref, n=9, bisections=6):
        """Samples (k, 2) and gaps (k,) of the windows zr0 (J, 2) +- w (J, 2): an n x n grid and the boundary of the
        overlap between grid neighbours; the window index (k,) of each sample."""
        J = len(zr0)
        t = np.linspace(-1.0, 1.0, n)
        T = np.stack(np.meshgrid(t, t, indexing="ij"), -1)
        z = zr0[:, None, None] + T[None] * w[:, None, None]  # (J, n, n, 2)
        jid = np.broadcast_to(np.arange(J)[:, None, None], z.shape[:-1])
        g = self._gap(z.reshape(-1, 2), phi1, trees, ref).reshape(z.shape[:-1])
        pts, gaps, ids = [z[np.isfinite(g)]], [g[np.isfinite(g)]], [jid[np.isfinite(g)]]
        v = np.isfinite(g)
        for ax in (1, 2):
            sl_a = (slice(None),) + (slice(None, -1) if ax == 1 else slice(None),) + \
                (slice(None) if ax == 1 else slice(None, -1),)
            sl_b = (slice(None),) + (slice(1, None) if ax == 1 else slice(None),) + \
                (slice(None) if ax == 1 else slice(1, None),)
            f = v[sl_a] != v[sl_b]
            a, b, va = z[sl_a][f], z[sl_b][f], v[sl_a][f]
            pin, pout = np.where(va[:, None], a, b), np.where(va[:, None], b, a)
            gin = np.where(va, g[sl_a][f], g[sl_b][f])
            for _ in range(bisections):
                mid = 0.5 * (pin + pout)
                gm = self._gap(mid, phi1, trees, ref)
                c = np.isfinite(gm)
                pin, pout = np.where(c[:, None], mid, pin), np.where(c[:, None], pout, mid)
                gin = np.where(c, gm, gin)
            pts.append(pin), gaps.append(gin), ids.append(jid[sl_a][f])
        return np.concatenate(pts), np.concatenate(gaps), np.concatenate(ids)

    def first_touch(self, phi1, drive, ref, starts=6, levels=9, report=False):
        """Gear rotation phi2 (rad) at which the gear turned back onto the pinion (pinion at rotation ``phi1``) first
        touches the real flanks: the extremum of the angular gap in the driven direction (max of -drive phi2) over
        the overlap; NaN where the projections do not overlap. ``ref``: an estimate of phi2 (selects the 2 pi
        turn). The ``starts`` best samples of distinct parts of the overlap are refined over ``levels`` zoom levels.
        With ``report``, also the (z, rho) of the touch and the coarse best."""
        trees = [self._lookup(m, phi1) for m in (0, 1)]
        zr, lead = [], []
        for m in (0, 1):
            q = self._flank_samples(m)
            z = self._map(m, q, np.full(len(q), phi1))[:, :2]
            g = self._gap(z, phi1, trees, ref)
            ok = np.isfinite(g)
            zr.append(z[ok]), lead.append(-drive * g[ok])
        zr, lead = np.concatenate(zr), np.concatenate(lead)
        if not len(lead):
            return (np.nan, None, None) if report else np.nan
        # distinct parts: the best sample, then the best one farther than a few grid spacings from those taken
        span = np.ptp(zr, axis=0)
        cell = span / np.array(self.n).max()
        order = np.argsort(-lead)
        taken = []
        for i in order:
            if all(np.max(np.abs(zr[i] - zr[t]) / cell) > 4 for t in taken):
                taken.append(i)
            if len(taken) == starts:
                break
        c = zr[taken].copy()
        best = lead[taken].copy()
        w = np.tile(2 * cell, (len(c), 1))
        for level in range(levels):
            # boundary points of the overlap to 1/64 of the window's half width, of the last window to 2^-24 of it
            p, g, ids = self._window(c, w, phi1, trees, ref, bisections=24 if level == levels - 1 else 6)
            lw = -drive * g
            for j in range(len(c)):
                s = ids == j
                if not s.any():
                    continue
                k = np.argmax(np.where(s, lw, -np.inf))
                moved = np.any(np.abs(p[k] - c[j]) > 0.99 * w[j])
                if lw[k] >= best[j]:
                    best[j], c[j] = lw[k], p[k]
                if not moved:
                    w[j] /= 4
        j = int(np.argmax(best))
        phi2 = -drive * best[j]
        return (phi2, c[j], zr[order[0]]) if report else phi2


def tca_deviation(c1, c2, kin, res, idx, misalignment=None, n=(90, 45), k=6, starts=4, levels=10):
    """TCA's lead minus the oracle's first touch over every tooth pair of ``res`` (arcsec) at positions ``idx``
    (lead = -drive phi2; pair k: pinion rotation phi1 + 2 pi k / z1, gear rotation + 2 pi k / z2)."""
    from spiralbevel.meshing.misalignment import Misalignment
    from spiralbevel.meshing.tca_result import ARCSEC

    mis = Misalignment() if misalignment is None else misalignment
    o = GapOracle(c1, c2, flank_box(c1), flank_box(c2), mis.axes(kin.shaft_angle), n=n, k=k)
    out = []
    for i in idx:
        leads = []
        for kk in res.pairs:
            pe = res.phi1[i] + 2 * np.pi * kk / kin.z1
            p2 = o.first_touch(pe, res.drive_sign, -kin.z1 / kin.z2 * pe, starts=starts, levels=levels)
            leads.append(-res.drive_sign * (p2 + 2 * np.pi * kk / kin.z2))
        out.append((-res.drive_sign * res.phi2[i] - np.nanmax(leads)) / ARCSEC)
    return np.array(out)
