"""Brute-force oracle of tooth contact analysis, independent of the library's TCA code.

At a pinion rotation, every point of either real flank (a dense grid of the flank's parameter box, kept where the
surface's ``contains`` holds, plus the flank boundary found by bisection of ``contains`` between grid neighbours) is
carried along the relative motion until it lies on the other member's flank: a pinion point turns with the pinion
and is met by the gear flank at the gear rotation where the gear surface passes through it; a gear point is carried
by the gear rotation until it lies on the pinion flank. Each such meeting (a plain 3 x 3 Newton solve in the other
member's surface parameters and the gear rotation, finite-difference Jacobian) counts if the met point is on the
other member's real flank. The gear, turned back onto the pinion, first touches the real teeth at the meeting that
leads furthest in the driven direction: the oracle's contact is the maximum of -drive * phi2 over all meetings and
tooth pairs. The coarse maximum is then refined by zooming grids (factor 4 per level) around the best point of each
member, boundary points included, so that an edge (a boundary curve against a flank) or a surface contact is found
alike. Only the surfaces' ``evaluate``/``contains``, the assembly axes of the misalignment model and numpy are used.
"""

from __future__ import annotations

import numpy as np


def _rz(a):
    c, s = np.cos(a), np.sin(a)
    R = np.zeros(np.shape(a) + (3, 3))
    R[..., 0, 0], R[..., 0, 1], R[..., 1, 0], R[..., 1, 1], R[..., 2, 2] = c, -s, s, c, 1.0
    return R


class Oracle:
    """Brute-force first touch of two real flanks (see the module docstring).

    pinion, gear : surfaces with ``evaluate(params) -> (points, normals)`` and ``contains(params)``, member frames;
    box1, box2 : ((lo0, hi0), (lo1, hi1)) parameter boxes that hold each real flank;
    z1, z2, axes : tooth numbers and the assembly ``(a1, o1, a2, o2, B2)`` (pinion turns about +z through o1, the gear
    about a2 through o2, gear member frame -> fixed by rot(a2, phi2) @ B2).
    """

    def __init__(self, pinion, gear, box1, box2, z1, z2, axes, n=(24, 12)):
        self.s = (pinion, gear)
        self.box = (np.asarray(box1, float), np.asarray(box2, float))
        self.z1, self.z2 = z1, z2
        self.a2, self.o1, self.o2, self.B2 = np.asarray(axes[2]), np.asarray(axes[1]), np.asarray(axes[3]), axes[4]
        self.n = n

    # ------------------------------------------------------------ motion
    def _gear_rot(self, phi2):
        """rot(a2, phi2) @ B2 (Rodrigues)."""
        a = self.a2
        K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
        phi2 = np.asarray(phi2, float)[..., None, None]
        R = np.eye(3) + np.sin(phi2) * K + (1 - np.cos(phi2)) * (K @ K)
        return R @ self.B2

    def _meet(self, m, pts, phi1, phi2_guess, q_guess):
        """Member m's points ``pts (k, 3)`` (member frame) at pinion rotations ``phi1 (k,)`` met by the other member's
        flank: (q_other (k, 2), phi2 (k,), ok (k,))."""
        other = self.s[1 - m]
        x = np.concatenate([q_guess, phi2_guess[:, None]], 1)
        R1 = _rz(phi1)

        def W(phi2, pts, R1):
            """The moving point in the other member's frame at gear rotation phi2."""
            R2 = self._gear_rot(phi2)
            if m == 0:  # pinion point in the fixed frame, then in the gear member frame
                p = self.o1 + np.einsum("kij,kj->ki", R1, pts)
                return np.einsum("kji,kj->ki", R2, p - self.o2)
            p = self.o2 + np.einsum("kij,kj->ki", R2, pts)  # gear point, then in the pinion member frame
            return np.einsum("kji,kj->ki", R1, p - self.o1)

        def F(x, pts, R1):
            return other.evaluate(x[:, 0:2])[0] - W(x[:, 2], pts, R1)

        def surf_jac(q):
            """Point and d point / d params (k, 3, 2) of the other flank (its own derivatives if it has them)."""
            if hasattr(other, "derivatives"):
                r, _, dr, _ = other.derivatives(q)
                return r, dr
            r = other.evaluate(q)[0]
            return r, np.stack([(other.evaluate(q + np.eye(2)[j] * 1e-6)[0] - r) / 1e-6 for j in range(2)], -1)

        lim = np.array([1.0, 0.05, 0.01])
        active = np.arange(len(x))
        for _ in range(30):
            xa, pa, Ra = x[active], pts[active], R1[active]
            r, dr = surf_jac(xa[:, 0:2])
            w = W(xa[:, 2], pa, Ra)
            f = r - w
            keep = np.all(np.isfinite(f), axis=1) & ~np.all(np.abs(f) < 1e-11, axis=1)
            active, xa, pa, Ra, f, dr, w = (v[keep] for v in (active, xa, pa, Ra, f, dr, w))
            if not active.size:
                break
            J = np.concatenate([dr, (-(W(xa[:, 2] + 1e-9, pa, Ra) - w) / 1e-9)[..., None]], -1)
            good = np.all(np.isfinite(J), axis=(1, 2))
            Jg = np.where(good[:, None, None], J, np.eye(3))
            good &= np.abs(np.linalg.det(Jg)) > 1e-300
            dx = np.linalg.solve(np.where(good[:, None, None], Jg, np.eye(3)),
                                 np.where(good[:, None], -f, 0.0)[..., None])[..., 0]
            x[active] = xa + np.clip(dx, -lim, lim)
            active = active[good]
        f = F(x, pts, R1)
        ok = np.all(np.abs(f) < 1e-10, axis=1) & other.contains(x[:, 0:2])
        return x[:, 0:2], x[:, 2], ok

    # ------------------------------------------------------------ samples
    def _samples(self, m, lo, hi, n, bisections=24):
        """Grid points of member m's flank in the boxes [lo, hi] (J, 2) plus the boundary points between grid
        neighbours: (points (k, 2), job index (k,))."""
        s = self.s[m]
        t0 = np.linspace(0, 1, n[0])
        t1 = np.linspace(0, 1, n[1])
        T = np.stack(np.meshgrid(t0, t1, indexing="ij"), -1)  # (n0, n1, 2)
        q = lo[:, None, None] + T[None] * (hi - lo)[:, None, None]  # (J, n0, n1, 2)
        job = np.broadcast_to(np.arange(len(lo))[:, None, None], q.shape[:-1])
        inside = s.contains(q)
        out, jobs = [q[inside]], [job[inside]]
        pin, pout, pj = [], [], []
        for sl_a, sl_b in (((slice(None), slice(None, -1)), (slice(None), slice(1, None))),
                           ((slice(None), slice(None), slice(None, -1)), (slice(None), slice(None), slice(1, None)))):
            a, b, ia, ib = q[sl_a], q[sl_b], inside[sl_a], inside[sl_b]
            flip = ia != ib
            pin.append(np.where(ia[flip][:, None], a[flip], b[flip]))
            pout.append(np.where(ia[flip][:, None], b[flip], a[flip]))
            pj.append(job[sl_a][flip])
        pin, pout, pj = np.concatenate(pin), np.concatenate(pout), np.concatenate(pj)
        if len(pin):
            for _ in range(bisections):
                mid = 0.5 * (pin + pout)
                c = s.contains(mid)
                pin, pout = np.where(c[:, None], mid, pin), np.where(c[:, None], pout, mid)
            out.append(pin)
            jobs.append(pj)
        return np.concatenate(out, 0), np.concatenate(jobs)

    def _best(self, m, q, job, phi1, drive, p2_guess, q_guess):
        """Best meeting per job of member m's points q (k, 2) of jobs ``job (k,)`` at the effective pinion rotations
        ``phi1 (J,)``: (lead (J,), q (J, 2), phi2 (J,), q_other (J, 2)); lead -inf where no point meets."""
        J = len(phi1)
        pts = self.s[m].evaluate(q)[0]
        qo, p2, ok = self._meet(m, pts, phi1[job], p2_guess[job], q_guess[job])
        # a second start for the misses: the solution of the nearest hit of the same job
        miss = np.flatnonzero(~ok)
        if miss.size and ok.any():
            src = np.full(miss.size, -1)
            for j in np.unique(job[miss]):
                hit = np.flatnonzero(ok & (job == j))
                if hit.size:
                    mj = miss[job[miss] == j]
                    src[np.searchsorted(miss, mj)] = hit[np.argmin(
                        np.linalg.norm(q[hit][None] - q[mj][:, None], axis=-1), axis=1)]
            use = src >= 0
            if use.any():
                mm, ss = miss[use], src[use]
                qo2, p22, ok2 = self._meet(m, pts[mm], phi1[job[mm]], p2[ss], qo[ss])
                qo[mm], p2[mm], ok[mm] = qo2, p22, ok2
        lead = np.where(ok, -drive * p2, -np.inf)
        best = np.full(J, -np.inf)
        np.maximum.at(best, job, lead)
        k = np.full(J, -1)
        for j in np.flatnonzero(np.isfinite(best)):
            sel = np.flatnonzero(job == j)
            k[j] = sel[np.argmax(lead[sel])]
        kk = np.maximum(k, 0)
        fin = k >= 0
        return (best, np.where(fin[:, None], q[kk], np.nan), np.where(fin, p2[kk], np.nan),
                np.where(fin[:, None], qo[kk], np.nan))

    def first_touch(self, phi1_eff, drive, guess, levels=6):
        """Leading meeting of the reference tooth pair at the effective pinion rotations ``phi1_eff (J,)``:
        (phi2_eff (J,) or NaN, member (J,) whose point leads: 0 pinion, 1 gear, -1 none). ``guess = (phi2_eff (J,),
        q1 (2,), q2 (2,))`` starts the Newton solves."""
        phi1_eff = np.atleast_1d(np.asarray(phi1_eff, float))
        J = len(phi1_eff)
        lead_best = np.full(J, -np.inf)
        p2_best = np.full(J, np.nan)
        mem = np.full(J, -1)
        for m in (0, 1):
            lo, hi = self.box[m][:, 0], self.box[m][:, 1]
            if not hasattr(self, "_coarse"):
                self._coarse = {}
            if m not in self._coarse:
                self._coarse[m] = self._samples(m, lo[None], hi[None], self.n, 40)[0]
            qc = self._coarse[m]
            q = np.tile(qc, (J, 1))
            job = np.repeat(np.arange(J), len(qc))
            qg = np.tile(np.asarray(guess[2] if m == 0 else guess[1], float), (J, 1))
            lead, qb, p2, qo = self._best(m, q, job, phi1_eff, drive, np.asarray(guess[0], float), qg)
            step = np.tile((hi - lo) / (np.array(self.n) - 1), (J, 1))
            level = np.zeros(J, int)
            alive = np.isfinite(lead)
            for _ in range(4 * levels):
                a = np.flatnonzero(alive)
                if not a.size:
                    break
                qs, js = self._samples(m, qb[a] - 2 * step[a], qb[a] + 2 * step[a], (9, 9))
                qs = np.concatenate([qs, qb[a]], 0)
                js = np.concatenate([js, np.arange(a.size)])
                q0 = qb[a]
                l2, qb2, p22, qo2 = self._best(m, qs, js, phi1_eff[a], drive, p2[a], qo[a])
                better = l2 >= lead[a]
                lead[a] = np.where(better, l2, lead[a])
                qb[a] = np.where(better[:, None], qb2, qb[a])
                p2[a], qo[a] = np.where(better, p22, p2[a]), np.where(better[:, None], qo2, qo[a])
                # the best point on the window's border (a long flat ridge): move the window, keep its size
                moved = np.any(np.abs(qb[a] - q0) > 1.99 * step[a], axis=1)
                step[a] = np.where(moved[:, None], step[a], step[a] / 4)
                level[a] += ~moved
                alive[a] = level[a] < levels
            win = lead > lead_best
            lead_best = np.where(win, lead, lead_best)
            p2_best = np.where(win, p2, p2_best)
            mem = np.where(win, m, mem)
        return p2_best, mem


def grid_box(surface, margin=0.02):
    """Parameter box (2, 2) of a phased generated surface's real flank: the range of the flank's own 31 x 15 grid,
    widened by ``margin`` of it at each end. The first parameter is the cutter angle phi of the (phi, psi_c) chart, or
    u of the (u, psi_c) chart for a surface without ``cutter_angle`` (the multi-point control's)."""
    g = surface.flank.grid(31, 15, curvature=False)
    phi = surface.cutter_angle(g.theta, g.psi_c) if hasattr(surface, "cutter_angle") else g.u
    lo, hi = np.array([phi.min(), g.psi_c.min()]), np.array([phi.max(), g.psi_c.max()])
    d = margin * (hi - lo)
    return np.stack([lo - d, hi + d], 1)


def first_touch_phi2(oracle, res, idx):
    """The oracle's gear rotation (J, P) rad of the first touch of each tooth pair of the TCA result ``res`` at its
    positions ``idx`` (J,), in the TCA's gear angle (the pair's pitch added back); NaN where a pair does not touch."""
    P = np.asarray(res.pairs)
    phi = res.phi1[idx][:, None] + 2 * np.pi * P / oracle.z1
    pinion, gear = oracle.s
    p2e, _ = oracle.first_touch(phi.ravel(), res.drive_sign,
                                (-oracle.z1 / oracle.z2 * phi.ravel(), pinion.reference_params, gear.reference_params))
    return p2e.reshape(phi.shape) + 2 * np.pi * P / oracle.z2


def lead_deviation(oracle, res, idx):
    """TCA minus oracle leading contact (J,) rad of the gear at the positions ``idx``: lead = -drive * phi2 of the
    contact that leads over the tooth pairs."""
    p2 = first_touch_phi2(oracle, res, idx)
    lead = np.max(np.where(np.isfinite(p2), -res.drive_sign * p2, -np.inf), axis=1)
    return -res.drive_sign * res.phi2[idx] - lead
