"""The registry of compiled surface jets: one dispatch that the compiled TCA Newton calls for every surface.

A surface plugs its compiled jet into TCA by exposing ``jet = (kind, prm)``: ``kind`` an integer of this registry and
``prm (k,) float`` its parameter vector. :func:`surface_jet` writes the jet at one parameter point into
``out (3, 6)`` with the columns (r, n, r_q0, r_q1, n_q0, n_q1), member frame, mm and outward unit normal.

Registered kinds:

* :data:`LOGSPIRAL` (0): the log-spiral flank, :mod:`spiralbevel._core.logspiral_jet`.
* :data:`GENERATED` (1): the face-milled generated flank in the (phi, psi_c) chart,
  :mod:`spiralbevel._core.generation_blade_jet`.
* :data:`NORMAL_QUADRATIC` (2): a log-spiral flank crowned along its normal by a quadratic deviation
  (``NormalDeviation`` with ``quadratic_crowning``), :mod:`spiralbevel._core.normal_deviation_jet`.

Adding a kind is a new branch in :func:`surface_jet` and a ``jet`` property on
the surface class; surfaces without a compiled jet are evaluated by numpy between the compiled Newton steps
(:mod:`spiralbevel._core.tca_newton`). A dispatch on an integer (rather than passing compiled functions around) keeps
every kernel cacheable on disk.
"""

from __future__ import annotations

import math

from .jit import kernel
from .generation_blade_jet import blade_jet_point
from .logspiral_jet import logspiral_jet
from .normal_deviation_jet import normal_quadratic_jet

__all__ = ["LOGSPIRAL", "GENERATED", "NORMAL_QUADRATIC", "surface_jet"]

LOGSPIRAL = 0
GENERATED = 1
NORMAL_QUADRATIC = 2


@kernel(inline="always")   # a branch on kind: inlined into its callers, which then link the jets directly
def surface_jet(kind, prm, q0, q1, out):
    """Jet of surface ``kind`` with parameters ``prm`` at (q0, q1) into ``out (3, 6)``; NaN for an unknown kind."""
    if kind == LOGSPIRAL:
        logspiral_jet(prm, q0, q1, out)
    elif kind == GENERATED:
        blade_jet_point(prm, q0, q1, out)
    elif kind == NORMAL_QUADRATIC:
        normal_quadratic_jet(prm, q0, q1, out)
    else:
        for i in range(3):
            for j in range(6):
                out[i, j] = math.nan
