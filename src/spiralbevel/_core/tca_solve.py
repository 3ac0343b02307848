"""Python entry points of the compiled TCA Newton (:mod:`spiralbevel._core.tca_newton`): each allocates the arrays of
an operation and makes one call of the one kernel :func:`spiralbevel._core.tca_newton.newton_batch`.

* :func:`newton_jets` -- the whole batched iteration in compiled code for surfaces with compiled jets
  (:mod:`spiralbevel._core.jets`);
* :func:`continuation_jets` -- the continuation of TCA's path of contact (its nodes and tangents) in one call for
  such surfaces;
* :class:`Iteration` -- the same iteration as reverse communication for surfaces without one: the caller evaluates
  the surfaces at the trial points (by numpy, :meth:`spiralbevel.meshing.contact_problem.ContactProblem.newton`);
* :func:`step_batch`, :func:`tangent_batch`, :func:`singular_batch` -- the Newton step
  (:func:`spiralbevel._core.tca_step.step`), the path tangent and the line-contact test of a batch of systems.

Every array handed to the kernel is a writable, aligned, C-contiguous float64 (int64, bool) array, and arrays an
operation does not use are empty ones of the same types: one argument signature, compiled once (``_core/jit.py``).
"""

from __future__ import annotations

import numpy as np

from .tca_newton import (ACCEPT, ADVANCE, BEGIN, CONTINUE, FAIL, HAVE_E, IT, JETS, MODE, SINGULAR, START, STEP,
                         TANGENT, C, newton_batch)

__all__ = ["newton_jets", "continuation_jets", "Iteration", "step_batch", "tangent_batch", "singular_batch"]


_F1, _F2, _F3 = np.empty(0), np.empty((0, 0)), np.empty((0, 0, 0))
_I1, _B1 = np.empty(0, np.int64), np.empty(0, np.bool_)
#: the arguments of newton_batch after ``iv, fv``, with the empty array that stands for an unused one
_ARGS = {"p1": _F1, "p2": _F1, "c1": _F1, "s1": _F1, "aval": _F1, "d": _F1, "M2": _F2, "x": _F2, "E": _F3, "F": _F2,
         "J": _F3, "S1": _F3, "S2": _F3, "S1f": _F3, "Q": _F3, "xn": _F2, "Fn": _F2, "Jn": _F3, "T1": _F3, "T2": _F3,
         "T1f": _F3, "TQ": _F3, "dx": _F2, "res": _F1, "best": _F1, "stall": _I1, "halved": _I1, "idx": _I1,
         "active": _B1, "acc": _B1}
_POS = {name: 2 + i for i, name in enumerate(_ARGS)}
_TEMPLATE = [None, None, *_ARGS.values()]
_P1, _P2, _C1, _S1, _AVAL, _D, _M2, _X, _E, _F, _J, _SS1, _SS2, _S1F, _Q = range(2, 17)
_DX, _ACTIVE = _POS["dx"], _POS["active"]
_F8 = np.dtype(np.float64)


def _args(mode, ints=(), fv=(0.0, 0.0, 0.0), **arrays):
    """Argument list of :func:`newton_batch`: the integer vector ``(mode, *ints)`` (zeros after), ``fv``, the given
    arrays and empty ones for the rest."""
    args = list(_TEMPLATE)
    args[0] = np.array((mode, *ints) + (0,) * (10 - len(ints)), np.int64)
    args[1] = np.array(fv, np.float64)
    for name, a in arrays.items():
        args[_POS[name]] = a
    return args


def _batch(mode, L, tol, rcond, J):
    """Argument list of :func:`newton_batch` for an operation on the systems ``J`` alone (no iteration)."""
    a = list(_TEMPLATE)
    a[0] = np.array((mode, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0), np.int64)
    a[1] = np.array((L, tol, rcond), np.float64)
    a[_J] = _arr(J)
    return a


def _arr(a):
    """``a`` as a writable, aligned, C-contiguous float64 array (copied only if needed): one argument type."""
    if type(a) is np.ndarray and a.dtype == _F8:
        f = a.flags
        if f.c_contiguous and f.writeable and f.aligned:
            return a
    return np.array(a, np.float64, order="C")


def newton_jets(kind1, p1, kind2, p2, c1, s1, x0, E, have_E, d, M2, L, aj, aval, tol, max_iter, rcond, patience,
                halvings):
    """The whole batched Newton for two surfaces with compiled jets (:func:`spiralbevel._core.jets.surface_jet`).

    Parameters
    ----------
    kind1, p1, kind2, p2 : int, (k,) float
        Jets of pinion and gear.
    c1, s1 : (M,) float
        cos, sin of the effective pinion angles.
    x0 : (M, 5) float
    E : (M, 2, 3) float
        Basis rows of the normal equations; filled from the gear normal at x0 unless ``have_E``.
    d, M2, L :
        Assembly constants (:mod:`spiralbevel._core.tca_newton`).
    aj, aval : int, (M,) float
        Anchor equation x_aj = aval (aj < 0: none).
    tol, max_iter, rcond, patience, halvings :
        See :mod:`spiralbevel._core.tca_newton`.

    Returns
    -------
    x (M, 5), F (M, k), J (M, k, 5), res (M,), S1, S2 (M, 3, 6), S1f (M, 3, 6), Q (M, 6, 6), iterations
    """
    M = x0.shape[0]
    k = 6 if aj >= 0 else 5
    a = list(_TEMPLATE)   # the work arrays left empty: newton_batch allocates them
    a[0] = np.array((JETS, kind1, kind2, bool(have_E), aj, max_iter, patience, halvings, 0, 0, 0), np.int64)
    a[1] = np.array((L, tol, rcond), np.float64)
    a[_P1], a[_P2], a[_C1], a[_S1], a[_AVAL], a[_D], a[_M2] = (_arr(p1), _arr(p2), _arr(c1), _arr(s1), _arr(aval),
                                                               _arr(d), _arr(M2))
    a[_X], a[_E] = np.array(x0, np.float64, order="C"), _arr(E)
    a[_F], a[_J] = F, J = np.empty((M, k)), np.empty((M, k, 5))
    a[_SS1], a[_SS2], a[_S1F], a[_Q] = S1, S2, S1f, Q = (np.empty((M, 3, 6)), np.empty((M, 3, 6)), np.empty((M, 3, 6)),
                                                       np.empty((M, 6, 6)))
    a[_POS["res"]] = res = np.empty(M)
    newton_batch(*a)
    return a[_X], F, J, res, S1, S2, S1f, Q, int(a[0][IT])


def continuation_jets(kind1, p1, kind2, p2, x_mean, xp0, d, M2, L, phi1_mean, h, need_lo, need_hi, tol, max_iter,
                      rcond, patience, halvings):
    """Nodes of the path of contact from the mean point ``x_mean (5,)`` with tangent ``xp0 (5,)`` out to ``need_lo``
    steps ``h`` (rad) below ``phi1_mean`` and ``need_hi`` above, for two surfaces with compiled jets
    (:func:`spiralbevel._core.tca_newton.continuation`; the other arguments as :func:`newton_jets`).

    Returns
    -------
    offsets (c,) rad, X (c, 5), Xp (c, 5), (fail_lo, fail_hi)
        The nodes (sorted offsets from phi1_mean, solutions, tangents dx/dphi1) and the offsets of the first node that
        could not be reached below and above (-inf, inf where none failed).
    """
    need_lo, need_hi = max(int(need_lo), 0), max(int(need_hi), 0)
    K = need_lo + need_hi + 1
    a = list(_TEMPLATE)
    a[0] = np.array((CONTINUE, kind1, kind2, 0, -1, max_iter, patience, halvings, 0, 0, 0, need_hi, need_lo), np.int64)
    a[1] = np.array((L, tol, rcond, phi1_mean, h, 0.0, 0.0), np.float64)
    a[_P1], a[_P2], a[_D], a[_M2] = _arr(p1), _arr(p2), _arr(d), _arr(M2)
    X, Xp, off = np.empty((K, 5)), np.empty((K, 5)), np.empty(K)
    X[need_lo], Xp[need_lo] = x_mean, xp0
    a[_X], a[_DX], a[_POS["res"]] = X, Xp, off
    newton_batch(*a)
    c = int(a[0][C])
    return off[:c], X[:c], Xp[:c], (float(a[1][FAIL]), float(a[1][FAIL + 1]))


class Iteration:
    """The batched Newton as reverse communication, for surfaces that the caller evaluates (by numpy).

    ``begin`` assembles the systems at the start and returns the number ``c`` of trial points ``xn[:c]`` (systems
    ``idx[:c]``); the caller evaluates the surfaces there and hands them to ``advance``, which returns the next ``c``;
    c = 0 when every system has converged, been given up or reached ``max_iter``
    (:func:`spiralbevel._core.tca_newton.newton_batch`).

    Parameters
    ----------
    M, k : int
        Number of systems, equations per system (6 with an anchor).
    c1, s1, E, d, M2, L, aj, aval, tol, max_iter, rcond, patience, halvings :
        As :func:`newton_jets`.

    Attributes
    ----------
    x (M, 5), F (M, k), J (M, k, 5), res (M,), E (M, 2, 3), S1f (M, 3, 6), Q (M, 6, 6) : float
        Iterates, their systems and residuals max|F| (inf: not finite), basis rows, fixed-frame data.
    xn (M, 5) float, idx (M,) int
        Trial points and their systems (the first ``c``).
    accepted (M,) bool
        Which of the last ``c`` trials were taken (the others are retried with the step halved).
    iterations : int
    """

    def __init__(self, M, k, c1, s1, E, d, M2, L, aj, aval, tol, max_iter, rcond, patience, halvings):
        self.E = E = _arr(E)
        self.x, self.F, self.J = np.empty((M, 5)), np.empty((M, k)), np.empty((M, k, 5))
        self.S1f, self.Q = np.empty((M, 3, 6)), np.empty((M, 6, 6))
        self.res, self.accepted = np.empty(M), np.zeros(M, np.bool_)
        self.xn, self.idx = np.empty((M, 5)), np.empty(M, np.int64)
        #: the argument list of newton_batch, its integer vector first (updated in place by each call)
        self.args = _args(BEGIN, (0, 0, 0, aj, max_iter, patience, halvings), (L, tol, rcond), c1=_arr(c1),
                          s1=_arr(s1), aval=_arr(aval), d=_arr(d), M2=_arr(M2), x=self.x, E=E, F=self.F, J=self.J,
                          S1f=self.S1f, Q=self.Q, xn=self.xn, Fn=np.empty((M, k)), Jn=np.empty((M, k, 5)),
                          T1f=np.empty((M, 3, 6)), TQ=np.empty((M, 6, 6)), dx=np.zeros((M, 5)), res=self.res,
                          best=np.empty(M), stall=np.zeros(M, np.int64), halved=np.zeros(M, np.int64), idx=self.idx,
                          active=np.zeros(M, np.bool_), acc=self.accepted)

    @property
    def iterations(self) -> int:
        return int(self.args[0][IT])

    def _run(self, mode, **arrays):
        a = self.args
        a[0][MODE] = mode
        for name, v in arrays.items():
            a[_POS[name]] = v
        newton_batch(*a)
        return int(a[0][C])

    def begin(self, x0, S1=None, S2=None, have_E=False, F=None, J=None):
        """Start from ``x0 (M, 5)`` with the member-frame surface data ``S1, S2 (M, 3, 6)`` there (the basis rows
        ``E`` filled from the gear normal unless ``have_E``), or with the systems ``F, J`` given; returns c."""
        self.x[:] = x0
        self.args[0][HAVE_E] = bool(have_E)
        if S1 is None:
            self.F[:], self.J[:] = F, J
            return self._run(START)
        return self._run(BEGIN, S1=S1, S2=S2)

    def advance(self, T1=None, T2=None, Fn=None, Jn=None):
        """Apply the member-frame surface data ``T1, T2 (c, 3, 6)`` at the trial points (the accepted ones are copied
        into ``S1, S2`` of :meth:`begin`), or the systems ``Fn (c, k)``, ``Jn (c, k, 5)`` there; returns the next c."""
        if T1 is None:
            return self._run(ACCEPT, Fn=_arr(Fn), Jn=_arr(Jn))
        return self._run(ADVANCE, T1=T1, T2=T2)


def step_batch(J, F, rcond):
    """:func:`spiralbevel._core.tca_step.step` for every row of ``J (m, k, 5)``, ``F (m, k)``; returns ``dx (m, 5)``."""
    a = _batch(STEP, 0.0, 0.0, rcond, J)
    a[_F], a[_DX] = _arr(F), np.empty((a[_J].shape[0], 5))
    newton_batch(*a)
    return a[_DX]


def tangent_batch(J, S1f, E, L, rcond):
    """Path tangent dx/dphi1 (m, 5) = -J^+ dF/dphi1 from ``J (m, k, 5)`` and the fixed-frame pinion data
    ``S1f (m, 3, 6)``, basis rows ``E (m, 2, 3)`` (see :func:`spiralbevel._core.tca_newton.newton_batch`)."""
    a = _batch(TANGENT, L, 0.0, rcond, J)
    a[_S1F], a[_E], a[_DX] = _arr(S1f), _arr(E), np.empty((a[_J].shape[0], 5))
    newton_batch(*a)
    return a[_DX]


def singular_batch(J, tol):
    """Whether s_min / s_max of the column-equilibrated ``J (m, k, 5)`` is below ``tol``, per system (line contact;
    :func:`spiralbevel._core.tca_step.singular_rows`).

    Certificates first, the Jacobi SVD only where they do not decide: with unit columns s_max >= 1 and, for the
    triangular factor R of a QR decomposition, s_min <= min_j |R_jj|: singular when min_j |R_jj| < tol; regular when
    |det| = prod_j |R_jj| > 5^2.5 tol (see :func:`spiralbevel._core.tca_step.step`). Non-finite systems are not
    singular."""
    a = _batch(SINGULAR, 0.0, tol, 0.0, J)
    a[_ACTIVE] = np.zeros(a[_J].shape[0], np.bool_)
    newton_batch(*a)
    return a[_ACTIVE]
