"""The Newton solution of TCA's edge and corner systems for a batch (:func:`solve_edge_contacts`), the equations of
:mod:`spiralbevel.meshing.tca_edge` and :mod:`spiralbevel._core.tca_corner`: compiled entirely where both surfaces
have compiled jets and margins (``jet``, ``boundary_jet``), else with the surfaces evaluated by numpy between the
compiled iterations (margins without ``boundary_jet``: ``boundary_margins`` with central differences)."""

from __future__ import annotations

import math

import numpy as np

from .._core import tca_batch as _b
from .._core import tca_edge as _ke
from .._core import tca_corner_screen as _kc
from .._core import tca_edge_stage as _kst
from .._core.jets import GENERATED
from .contact_surface import surface_contains, surface_derivatives

__all__ = ["solve_edge_contacts", "corner_split", "corner_index", "flank_contains"]

#: step of the forward difference of the curve tangent (surface parameters), and of the central difference of the
#: margin gradient of surfaces without compiled margins
_H_TAU = 1e-7
_H_PARAM = 1e-6
#: tolerance of the tangency equation where a margin gradient is a central difference (its round-off, about
#: 1e-16 |g| / _H_PARAM, is 1e-9 of the gradient; the TE is stationary along the curve at the root, so an error of
#: the tangency of 1e-9 moves the TE by its square)
_TOL_TANGENCY_FD = 1e-9
#: rank threshold of the Newton step (:func:`spiralbevel._core.tca_newton.step`)
_RCOND = 1e-12


def _boundary(surface):
    """``(kind, prm)`` of a surface's compiled margins, or None."""
    b = getattr(surface, "boundary_jet", None)
    if b is None:
        return None
    return int(b[0]), np.ascontiguousarray(b[1], float)


def _shares(kind, prm, b):
    """True where the margins ``b`` of a generated flank evaluate the surface's own jet ``(kind, prm)`` (the same
    parameters; a straight blade has NaN in its arc-centre slots, which are equal here). Kept for the last few pairs
    of parameter arrays (held, so that their ids are not reused)."""
    key = (kind, id(prm), id(b[1]))
    hit = _SHARES.get(key)
    if hit is not None and hit[0] is prm and hit[1] is b[1]:
        return hit[2]
    out = bool(kind == GENERATED and b[0] == _ke.MARGIN_GENERATED and b[1].shape[0] == prm.shape[0] + 8
               and np.array_equal(b[1][8:], prm, equal_nan=True))
    if len(_SHARES) >= 16:
        _SHARES.clear()
    _SHARES[key] = (prm, b[1], out)
    return out


_SHARES: dict[tuple, tuple] = {}   # (kind, id of the parameters, id of the margins) -> (parameters, margins, shares)


def _setup(prob):
    """Constants of the edge solves of one problem, computed once and kept on it: the compiled margins of both
    surfaces (or None), the numbers of boundaries (k1, K = k1 + k2, at least 1), whether the whole edge Newton runs in
    compiled code, and then whether each surface's margins share its jet (:func:`_shares`)."""
    s = prob.__dict__.get("_edge_setup")
    if s is None:
        b = (_boundary(prob.pinion), _boundary(prob.gear))
        k1 = len(getattr(prob.pinion, "boundary_names", ()))
        k2 = len(getattr(prob.gear, "boundary_names", ()))
        compiled = (prob._jets is not None and b[0] is not None and b[1] is not None
                    and k1 == k2 == _ke.N_MARGINS)
        shares = (_shares(*prob._jets[0], b[0]), _shares(*prob._jets[1], b[1])) if compiled else (False, False)
        s = (b, k1, max(1, k1 + k2), compiled, shares)
        prob._edge_setup = s
    return s


def compiled_args(prob):
    """Arguments of :func:`spiralbevel._core.tca_edge_screen.edge_try` fixed by the problem (kept on it): the kinds
    (6,), the jet and margin parameters of both members and their flank tests ``ctol (4,)``: the tolerances of
    ``contains`` as a margin test (-1 where ``contains`` is no such test) and the sheet sign of a generated flank's
    limit-line test ``on_sheet`` (0 for a surface without one); None where the edge Newton does not run entirely in
    compiled code."""
    s = prob.__dict__.get("_edge_args")
    if s is None:
        (b1, b2), _, _, compiled, (sh1, sh2) = _setup(prob)
        if not compiled:
            s = ()
        else:
            (k1, p1), (k2, p2) = prob._jets
            ct = [_flank_test(sf, sh) for sf, sh in ((prob.pinion, sh1), (prob.gear, sh2))]
            s = (np.array([k1, b1[0], int(sh1), k2, b2[0], int(sh2)], np.int64), np.ascontiguousarray(p1, float),
                 b1[1], np.ascontiguousarray(p2, float), b2[1],
                 np.array([-1.0 if t is None else t[0] for t in ct] + [0.0 if t is None else t[1] for t in ct]))
        prob._edge_args = s
    return s or None


def _flank_test(surface, shares):
    """(margin tolerance, sheet sign) of ``surface.contains`` as the compiled screen applies it, or None where it
    cannot: ``contains`` is "every margin >= -tol" (``contains_margin_tol``) and, with a limit-line test
    ``on_sheet``, the orientation of the chart's tangents has the sign ``_sheet_sign()`` of the mean point (±1), read
    from the jet that the margins evaluate (``shares``)."""
    tol = getattr(surface, "contains_margin_tol", None)
    if tol is None:
        return None
    if not hasattr(surface, "on_sheet"):
        return float(tol), 0.0
    sign = getattr(surface, "_sheet_sign", None)
    sign = sign() if shares and sign is not None else math.nan
    return (float(tol), float(sign)) if sign in (1.0, -1.0) else None


def flank_contains(surface, q):
    """``surface.contains(q)`` for ``q (m, 2)`` (all True without ``contains``): from one compiled call
    (:func:`spiralbevel._core.tca_edge.margins_batch`: the margins and the orientation of their jet, the test of the
    edge screen) where the surface's ``contains`` is its compiled margin test, with the limit-line test of a generated
    flank; else the surface's own method."""
    b = _boundary(surface) if getattr(surface, "contains_margin_tol", None) is not None else None
    if b is None:
        return surface_contains(surface, q)
    t = getattr(surface, "_flank_test_src", None)
    if t is None or t[0] is not b[1]:   # kept with the margin parameters it was derived for
        jet = getattr(surface, "jet", None)
        shares = jet is not None and _shares(int(jet[0]), np.asarray(jet[1], float), b)
        t = (b[1], _flank_test(surface, shares))
        try:
            surface._flank_test_src = t
        except AttributeError:   # a frozen surface: derived again at the next call
            pass
    if t[1] is None:
        return surface_contains(surface, q)
    tol, sheet = t[1]
    g, _, o = _ke.margins_batch(b[0], b[1], np.ascontiguousarray(q, float).reshape(-1, 2))
    with np.errstate(invalid="ignore"):
        out = (g >= -tol).all(axis=1)
        if sheet != 0.0:
            out &= o * sheet > 0.0
    return out


#: corner systems of the pinion's fillet junction against the gear's toe, heel or top edge that the proof of
#: :mod:`spiralbevel._core.tca_corner_screen` shows to have no root are not solved (False: every system is solved)
CORNER_PROOF = True
_NO_JUNCTION = np.zeros((0, 3))


def _junction_curve(mprm, q0):
    """Parameters (n, 2) of the fillet junction curve (u = u_j) of a generated flank with margins ``mprm`` (kind
    ``MARGIN_GENERATED``) at n = :data:`~spiralbevel._core.tca_corner_screen.N_SAMPLES` cone distances R evenly from
    R_i - b w to R_e + b w (w = R_e - R_i, b = :data:`~spiralbevel._core.tca_corner_screen.BEYOND`), or None where a
    point is not found. Each point solves R(q) = R_k and u(q) = u_j (margins toe and fillet, analytic gradients) by
    Newton to 1e-11, the middle one from ``q0 (2,)``, the others marched outward from it (steps of at most 0.5 rad).
    Run once per flank (a few hundred calls of the compiled margins)."""
    n, Ri, Re = _kc.N_SAMPLES, float(mprm[2]), float(mprm[3])
    w = Re - Ri
    out = np.empty((n, 2))
    mid = n // 2
    x = np.empty((1, 2))
    for k in [mid] + [k for d in range(1, n) for k in (mid + d, mid - d) if 0 <= k < n]:
        x[0] = q0 if k == mid else out[k - 1 if k > mid else k + 1]
        R = Ri - _kc.BEYOND * w + (1.0 + 2.0 * _kc.BEYOND) * w * k / (n - 1)
        for _ in range(31):
            g, dg, _ = _ke.margins_batch(_ke.MARGIN_GENERATED, mprm, x)
            f0, f1 = float(g[0, 0]) + Ri - R, float(g[0, _kc.FILLET])
            a, b, c, d = dg[0, 0, 0], dg[0, 0, 1], dg[0, _kc.FILLET, 0], dg[0, _kc.FILLET, 1]
            det = float(a * d - b * c)
            if not (math.isfinite(f0) and math.isfinite(f1) and math.isfinite(det)) or det == 0.0:
                return None
            if max(abs(f0), abs(f1)) < 1e-11:
                break
            d0, d1 = (f0 * d - f1 * b) / det, (a * f1 - c * f0) / det
            s = min(1.0, 0.5 / max(abs(d0), abs(d1), 1e-300))
            x[0, 0] -= s * d0
            x[0, 1] -= s * d1
        else:
            return None
        out[k] = x[0]
    return out


def junction_samples(prob, member, edge):
    """Samples (k, 3) mm of the pinion's fillet junction curve (pinion frame) for the corner proof of
    :func:`spiralbevel._core.tca_corner_screen.corner_excluded`, computed once per flank (kept on it with the margin
    parameters they were computed for, and on ``prob``); k = 0 (no proof) where the pinion is no generated flank with
    compiled margins or its junction curve is not found, and, before they are computed, where none of the systems
    ``(member (m,), edge (m,))`` is such a corner (``edge_try`` reads the samples only at those corners)."""
    got = prob.__dict__.get("_junction")
    if got is not None:
        return got
    (b, _), k1, K, _, _ = _setup(prob)
    if not CORNER_PROOF or b is None or b[0] != _ke.MARGIN_GENERATED or k1 != _ke.N_MARGINS:
        prob._junction = _NO_JUNCTION
        return _NO_JUNCTION
    surface = prob.pinion
    cached = getattr(surface, "_junction_src", None)
    if cached is None or cached[0] is not b[1]:
        lo = corner_index(prob, (0, _kc.FILLET), (1, 0))   # ... with the gear's toe, heel (lo + 1) and top (lo + 2)
        if not np.any((member == 0) & (edge >= lo) & (edge <= lo + 2)):
            return _NO_JUNCTION
        q = _junction_curve(b[1], np.asarray(surface.reference_params, float))
        cached = (b[1], _NO_JUNCTION if q is None else np.ascontiguousarray(surface.evaluate(q)[0]), q)
        try:
            surface._junction_src = cached
        except AttributeError:   # a frozen surface: sampled again for the next problem
            pass
    prob._junction = cached[1]
    return cached[1]


#: placeholders of the stage's arguments of ``edge_stage_run`` when it only solves (mode 0)
_NO_STAGE = None


def _no_stage():
    global _NO_STAGE
    if _NO_STAGE is None:
        f0 = np.zeros(0)
        _NO_STAGE = (np.zeros((0, 0), np.int64), np.zeros((0, 0)), f0, f0, np.zeros((0, 0)), np.zeros((0, 0)),
                     np.zeros((0, 0, 5)), np.zeros((0, 0, 3), np.int64), np.zeros(1, np.int64))
    return _NO_STAGE


def margins_of(prob, member, q):
    """All boundary margins (m, k) of the pinion (``member`` 0) or gear (1) of ``prob`` at ``q (m, 2)``."""
    return _all_margins((prob.pinion, prob.gear)[member], q, _setup(prob)[0][member])


def _all_margins(surface, q, b=False):
    """All boundary margins (m, k) of ``surface`` at ``q (m, 2)``: compiled where it has ``boundary_jet`` (``b``: that
    jet, or None, when the caller knows it)."""
    if b is False:
        b = _boundary(surface)
    if b is not None:
        return _ke.margins_batch(b[0], b[1], np.ascontiguousarray(q, float))[0]
    with np.errstate(invalid="ignore"):
        return np.asarray(surface.boundary_margins(q), float)


def _margin_jets(surface, q, e):
    """Margin ``e (m,)`` and its gradient of ``surface`` at ``q (m, 2)``: (g (m,), dg (m, 2))."""
    b = _boundary(surface)
    m = np.arange(len(q))
    if b is not None:
        g, dg, _ = _ke.margins_batch(b[0], b[1], np.ascontiguousarray(q, float))
        return g[m, e], dg[m, e]
    h = _H_PARAM
    st = np.stack([q, q + (h, 0), q - (h, 0), q + (0, h), q - (0, h)], 0)  # (5, m, 2)
    with np.errstate(invalid="ignore"):
        g = np.asarray(surface.boundary_margins(st), float)[:, m, e]  # (5, m)
    return g[0], np.stack([(g[1] - g[2]) / (2 * h), (g[3] - g[4]) / (2 * h)], -1)


def _newton_numpy(prob, c1, s1, x, member, edge, corner, tol, max_iter):
    """The edge and corner Newton with the surfaces evaluated by numpy between compiled iterations; ``x`` updated in
    place. ``corner (m, 4)``: (ma, ea, mb, eb) of a corner row (member 0), -1 elsewhere."""
    m = len(x)
    conv = np.zeros(m, bool)
    ndot = np.full(m, np.nan)
    active = np.ones(m, bool)
    h = _H_TAU
    pert = np.array([[0, 0], [h, 0], [0, h]], float)
    surfs = (prob.pinion, prob.gear)
    d, M2, _ = prob._const
    tol_t = _ke.TOL_TANGENCY if all(_boundary(sf) is not None for sf in surfs) else _TOL_TANGENCY_FD
    for _ in range(max_iter + 1):
        a = np.flatnonzero(active)
        if not a.size:
            break
        k = a.size
        SA, SB = np.empty((k, 3, 3, 6)), np.empty((k, 3, 6))
        gA, dgA = np.empty((k, 3)), np.empty((k, 3, 2))
        gB, dgB = np.zeros(k), np.zeros((k, 2))
        for A in (0, 1):
            s = member[a] == A
            if not s.any():
                continue
            qa = (x[a[s], 2 * A:2 * A + 2][:, None, :] + pert).reshape(-1, 2)
            with np.errstate(all="ignore"):
                SA[s] = _b.stack_state(*surface_derivatives(surfs[A], qa)).reshape(-1, 3, 3, 6)
                SB[s] = _b.stack_state(*surface_derivatives(surfs[1 - A], x[a[s], 2 - 2 * A:4 - 2 * A]))
                g, dg = _margin_jets(surfs[A], qa, np.repeat(edge[a[s]], 3))
            gA[s], dgA[s] = g.reshape(-1, 3), dg.reshape(-1, 3, 2)
        ca = corner[a]
        for col, g_, dg_ in ((0, gA[:, 0], dgA[:, 0]), (2, gB, dgB)):  # a corner: its two margins
            for mm in (0, 1):
                c = ca[:, col] == mm
                if c.any():
                    with np.errstate(all="ignore"):
                        g_[c], dg_[c] = _margin_jets(surfs[mm], x[a[c], 2 * mm:2 * mm + 2], ca[c, col + 1])
        cols = np.ascontiguousarray(np.where(ca[:, 0:1] >= 0, 2 * ca[:, 0::2], -1), np.int64)
        xa = np.ascontiguousarray(x[a])
        state, nd = np.empty(k, np.int64), np.empty(k)
        with np.errstate(all="ignore"):
            _ke.edge_step_batch(SA, gA, dgA, SB, gB, dgB, np.ascontiguousarray(member[a]), cols, c1[a], s1[a], xa,
                                d, M2, h, tol, tol_t, _RCOND, state, nd)
        x[a], ndot[a] = xa, nd
        conv[a[state == 1]] = True
        active[a[state != 0]] = False
    return conv, ndot


def corner_split(prob, member, edge):
    """Corner systems among ``(member (m,), edge (m,))``: member 0 with an edge index k1 + a K + b past the pinion's
    k1 boundaries (K = k1 + k2 boundaries of both members, :func:`corner_index`) is the corner where boundary a meets
    boundary b, both numbered over the pinion's boundaries then the gear's.

    Returns
    -------
    corner : (m,) bool
    ma, ea, mb, eb : (m,) int
        Member (0 pinion, 1 gear) and boundary index of a and of b (0 where not a corner).
    """
    _, k1, K, _, _ = _setup(prob)
    member, edge = np.asarray(member), np.asarray(edge)
    corner = (member == 0) & (edge >= k1)
    c = np.where(corner, edge - k1, 0)
    a, b = c // K, c % K
    ma, mb = (a >= k1).astype(int), (b >= k1).astype(int)
    return corner, ma, a - k1 * ma, mb, b - k1 * mb


def corner_index(prob, a, b):
    """The edge index (with member 0) of the corner where boundary ``a = (member, index)`` meets ``b``: two
    boundaries of different members (their curves meet) or of the same member (its flank's vertex touches the
    other flank)."""
    _, k1, K, _, _ = _setup(prob)
    return k1 + (a[0] * k1 + a[1]) * K + b[0] * k1 + b[1]


def solve_edge_contacts(prob, phi1_eff, x0, member, edge, tol=1e-10, max_iter=30):
    """Newton solution of the edge-contact equations (module docstring) for a batch of systems, corner systems
    (:mod:`spiralbevel._core.tca_corner`: two boundary curves meeting) among them.

    Parameters
    ----------
    prob : ContactProblem
        The assembled pair (surfaces with ``boundary_margins``).
    phi1_eff : (m,) float, rad
        Effective pinion rotations (pair k: phi1 + 2 pi k / z1).
    x0 : (m, 5) float
        Starting points (q1, q2, phi2_eff), e.g. the surface contact beyond the boundary.
    member : (m,) int
        0: a boundary curve of the pinion against the gear flank; 1: of the gear against the pinion flank.
    edge : (m,) int
        Index into that member's ``boundary_names``; with member 0, an index :func:`corner_index` past the pinion's
        boundaries is a corner (the pinion's boundary e1 meets the gear's boundary e2, :func:`corner_split`).
    tol : float, mm
        Tolerance on the point coincidence (the boundary equation to 1e-12, the tangency to 1e-11:
        :mod:`spiralbevel._core.tca_edge`).
    max_iter : int
        Newton iterations at most (a step is limited to 2 parameter units and 0.05 rad of phi2).

    Returns
    -------
    x : (m, 5) float
    converged : (m,) bool
    ndot : (m,) float
        n1 . n2 of the fixed-frame unit normals at x (about -1 at a contact).
    """
    phi1_eff = np.asarray(phi1_eff, float).reshape(-1)
    x = np.array(x0, float, order="C").reshape(-1, 5)
    member = np.ascontiguousarray(member, np.int64)
    edge = np.ascontiguousarray(edge, np.int64)
    if len(x) == 0:
        return x, np.zeros(0, bool), np.zeros(0)
    c1, s1 = np.cos(phi1_eff), np.sin(phi1_eff)
    (b1, b2), k1, K, compiled, (sh1, sh2) = _setup(prob)
    if compiled:
        # a corner row codes boundaries a, b (numbered over both members) as k1 + a K + b (corner_split); with
        # N = k1 = k2 boundaries per member, the kernel's code m N + e of a boundary is that number itself. The
        # Newton runs through the edge stage's entry point (mode 0: its solve alone), one compiled entry point for
        # the edge systems (spiralbevel._core.tca_edge_stage)
        kinds, p1, mp1, p2, mp2, ctol = compiled_args(prob)
        d, M2, _ = prob._const
        m = len(x)
        conv, ndot = np.empty(m, bool), np.empty(m)
        fp = np.zeros(_kst.FP_SIZE)
        fp[0:3] = _H_TAU, tol, _RCOND
        ip = np.zeros(_kst.IP_SIZE, np.int64)
        ip[1] = max_iter
        _kst.edge_stage_run(kinds, p1, mp1, p2, mp2, ctol, junction_samples(prob, member, edge), d, M2, fp, ip, c1, s1,
                            x, member, edge, conv, ndot, *_no_stage())
        return x, conv, ndot
    corner, ma, ea, mb, eb = corner_split(prob, member, edge)
    cols = np.where(corner[:, None], np.stack([ma, ea, mb, eb], 1), -1)
    conv, ndot = _newton_numpy(prob, c1, s1, x, member, np.where(corner, 0, edge), cols, tol, max_iter)
    return x, conv, ndot
