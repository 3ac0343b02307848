"""Python entry points of the compiled TCA Newton (:mod:`spiralbevel._core.tca_newton`): each allocates the arrays of
an operation and makes one call of the one kernel :func:`spiralbevel._core.tca_newton.newton_batch`.

* :func:`newton_jets` -- the whole batched iteration in compiled code for surfaces with compiled jets
  (:mod:`spiralbevel._core.jets`);
* :class:`Iteration` -- the same iteration as reverse communication for surfaces without one: the caller evaluates
  the surfaces at the trial points (by numpy, :meth:`spiralbevel.meshing.contact_problem.ContactProblem.newton`);
* :func:`step_batch`, :func:`tangent_batch`, :func:`singular_batch` -- the Newton step
  (:func:`spiralbevel._core.tca_step.step`), the path tangent and the line-contact test of a batch of systems.

Every array handed to the kernel is a writable, aligned, C-contiguous float64 (int64, bool) array, and arrays an
operation does not use are empty ones of the same types: one argument signature, compiled once (``_core/jit.py``).
"""

from __future__ import annotations

import numpy as np

from .tca_newton import (ACCEPT, ADVANCE, BEGIN, C, IT, JETS, MODE, SINGULAR, START, STEP, TANGENT, newton_batch)

__all__ = ["newton_jets", "Iteration", "step_batch", "tangent_batch", "singular_batch"]


_F1, _F2, _F3 = np.empty(0), np.empty((0, 0)), np.empty((0, 0, 0))
_I1, _B1 = np.empty(0, np.int64), np.empty(0, np.bool_)
_ARGS = {"p1": _F1, "p2": _F1, "c1": _F1, "s1": _F1, "aval": _F1, "d": _F1, "M2": _F2, "x": _F2, "E": _F3, "F": _F2,
         "J": _F3, "S1": _F3, "S2": _F3, "S1f": _F3, "Q": _F3, "xn": _F2, "Fn": _F2, "Jn": _F3, "T1": _F3, "T2": _F3,
         "T1f": _F3, "TQ": _F3, "dx": _F2, "res": _F1, "best": _F1, "stall": _I1, "halved": _I1, "idx": _I1,
         "active": _B1, "acc": _B1}


def _call(mode, ints=(), fv=(0.0, 0.0, 0.0), **arrays):
    """:func:`newton_batch` with the integer vector ``(mode, *ints)`` (zeros after) and empty unused arrays."""
    iv = np.zeros(11, np.int64)
    iv[MODE] = mode
    iv[1:1 + len(ints)] = ints
    newton_batch(iv, np.array(fv, float), *(arrays.get(n, e) for n, e in _ARGS.items()))
    return iv


def _arr(a):
    """``a`` as a writable, aligned, C-contiguous float64 array (copied only if needed): one argument type."""
    return np.require(a, np.float64, "CWA")


def _consts(d, M2):
    return _arr(d), _arr(M2)


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
    it = Iteration(M, k, c1, s1, E, d, M2, L, aj, aval, tol, max_iter, rcond, patience, halvings)
    it.x[:] = x0
    a = it.arrays
    S1, S2 = np.empty((M, 3, 6)), np.empty((M, 3, 6))
    iv = _call(JETS, (kind1, kind2, bool(have_E), aj, max_iter, patience, halvings), it.fv, p1=_arr(p1),
               p2=_arr(p2), S1=S1, S2=S2, T1=np.empty((M, 3, 6)), T2=np.empty((M, 3, 6)), **a)
    return it.x, it.F, it.J, it.res, S1, S2, it.S1f, it.Q, int(iv[IT])


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
        d, M2 = _consts(d, M2)
        self.fv = (float(L), float(tol), float(rcond))
        self.ints = (0, 0, 0, int(aj), int(max_iter), int(patience), int(halvings))
        c1, s1, aval, E = _arr(c1), _arr(s1), _arr(aval), _arr(E)
        self.x, self.E = np.empty((M, 5)), E
        self.F, self.J = np.empty((M, k)), np.empty((M, k, 5))
        self.S1f, self.Q = np.empty((M, 3, 6)), np.empty((M, 6, 6))
        self.res, self.accepted = np.empty(M), np.zeros(M, np.bool_)
        self.xn, self.idx = np.empty((M, 5)), np.empty(M, np.int64)
        self.arrays = dict(c1=c1, s1=s1, aval=aval, d=d, M2=M2, x=self.x, E=E, F=self.F, J=self.J, S1f=self.S1f,
                           Q=self.Q, xn=self.xn, Fn=np.empty((M, k)), Jn=np.empty((M, k, 5)), T1f=np.empty((M, 3, 6)),
                           TQ=np.empty((M, 6, 6)), dx=np.zeros((M, 5)), res=self.res, best=np.empty(M),
                           stall=np.zeros(M, np.int64), halved=np.zeros(M, np.int64), idx=self.idx,
                           active=np.zeros(M, np.bool_), acc=self.accepted)
        self.iterations = 0
        self._S = None

    def _run(self, mode, ints, **arrays):
        iv = _call(mode, ints, self.fv, **{**self.arrays, **arrays})
        self.iterations = int(iv[IT])
        self._iv = iv
        return int(iv[C])

    def begin(self, x0, S1=None, S2=None, have_E=False, F=None, J=None):
        """Start from ``x0 (M, 5)`` with the member-frame surface data ``S1, S2 (M, 3, 6)`` there (the basis rows
        ``E`` filled from the gear normal unless ``have_E``), or with the systems ``F, J`` given; returns c."""
        self.x[:] = x0
        ints = (0, 0, int(bool(have_E))) + self.ints[3:]
        if S1 is None:
            self.F[:], self.J[:] = F, J
            return self._run(START, ints)
        self._S = (S1, S2)
        return self._run(BEGIN, ints, S1=S1, S2=S2)

    def advance(self, T1=None, T2=None, Fn=None, Jn=None):
        """Apply the member-frame surface data ``T1, T2 (c, 3, 6)`` at the trial points (the accepted ones are copied
        into ``S1, S2`` of :meth:`begin`), or the systems ``Fn (c, k)``, ``Jn (c, k, 5)`` there; returns the next c."""
        ints = (0, 0, 0) + self.ints[3:] + (int(self._iv[C]), self.iterations)
        if T1 is None:
            return self._run(ACCEPT, ints, Fn=_arr(Fn), Jn=_arr(Jn))
        S1, S2 = self._S
        return self._run(ADVANCE, ints, S1=S1, S2=S2, T1=T1, T2=T2)


def step_batch(J, F, rcond):
    """:func:`spiralbevel._core.tca_step.step` for every row of ``J (m, k, 5)``, ``F (m, k)``; returns ``dx (m, 5)``."""
    J, F = _arr(J), _arr(F)
    dx = np.empty((J.shape[0], 5))
    _call(STEP, (), (0.0, 0.0, float(rcond)), J=J, F=F, dx=dx)
    return dx


def tangent_batch(J, S1f, E, L, rcond):
    """Path tangent dx/dphi1 (m, 5) = -J^+ dF/dphi1 from ``J (m, k, 5)`` and the fixed-frame pinion data
    ``S1f (m, 3, 6)``, basis rows ``E (m, 2, 3)`` (see :func:`spiralbevel._core.tca_newton.newton_batch`)."""
    J = _arr(J)
    dx = np.empty((J.shape[0], 5))
    _call(TANGENT, (), (float(L), 0.0, float(rcond)), J=J, S1f=_arr(S1f),
          E=_arr(E), dx=dx)
    return dx


def singular_batch(J, tol):
    """Whether s_min / s_max of the column-equilibrated ``J (m, k, 5)`` is below ``tol``, per system (line contact;
    :func:`spiralbevel._core.tca_step.singular_rows`).

    Certificates first, the Jacobi SVD only where they do not decide: with unit columns s_max >= 1 and, for the
    triangular factor R of a QR decomposition, s_min <= min_j |R_jj|: singular when min_j |R_jj| < tol; regular when
    |det| = prod_j |R_jj| > 5^2.5 tol (see :func:`spiralbevel._core.tca_step.step`). Non-finite systems are not
    singular."""
    J = _arr(J)
    out = np.zeros(J.shape[0], np.bool_)
    _call(SINGULAR, (), (0.0, float(tol), 0.0), J=J, active=out)
    return out
