"""The continuation and the exact transfer points of TCA in one compiled call each
(:func:`spiralbevel._core.tca_solve.continuation_jets`, :func:`spiralbevel._core.tca_transfer.transfer_points`) against
the same stages orchestrated in Python (the path taken by surfaces without compiled jets: ``meshing.tca._continuation``
level by level with ``ContactProblem.newton``, ``meshing.tca_transfer.exact_transfers`` with the Illinois bookkeeping
between batched solves), with the same compiled contact solves underneath: the rules are the same, so the results must
be equal bit for bit, on the face-milled pair (whose transfer meets an edge contact) and the crowned log-spiral pair,
aligned and misaligned, and from perturbed starts of the continuation."""

import numpy as np
import pytest

from _meshing_helpers import seed001_synthesized_pair

from spiralbevel.meshing import tca as tca_mod
from spiralbevel.meshing.contact_problem import ContactProblem
from spiralbevel.meshing.contact_surface import NormalDeviation, quadratic_crowning
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.misalignment import Misalignment
from spiralbevel.meshing.tca_surfaces import conjugate_logspiral_pair
from spiralbevel.meshing.tca_transfer import _compiled, exact_transfers


class _PythonPath:
    """A ContactProblem seen as one without compiled jets by the stages' dispatch (``_jets`` None), its Newton still
    the compiled one of the problem it wraps."""

    def __init__(self, prob):
        self._prob = prob
        self._jets = None

    def __getattr__(self, name):
        return getattr(self._prob, name)


@pytest.fixture(scope="module")
def pairs():
    c1, c2, kin = seed001_synthesized_pair()
    lp = conjugate_logspiral_pair()
    crowned = NormalDeviation(lp.pinion, quadratic_crowning(lp.pinion.reference_params, (0.5, 0.0, 5.0)))
    return {"face-milled": (c1, c2, kin, {"start": np.r_[c1.reference_params, c2.reference_params, 0.0]}),
            "crowned": (crowned, lp.gear, BevelPairKinematics(lp.shaft_angle, lp.z1, lp.z2), {})}


MISALIGNMENTS = [None, Misalignment(offset=0.05), Misalignment(gear_axial=-0.1, shaft_angle=0.002)]


def _captured(pinion, gear, kin, kw, mis):
    """solve_tca's arguments of _continuation and exact_transfers (and its result)."""
    got = {}
    cont, xfer = tca_mod._continuation, tca_mod.exact_transfers

    def c(*a, **k):
        got["cont"] = (a, k)
        return cont(*a, **k)

    def x(*a, **k):
        got["xfer"] = (a, k)
        return xfer(*a, **k)

    tca_mod._continuation, tca_mod.exact_transfers = c, x
    try:
        res = tca_mod.solve_tca(pinion, gear, kin, misalignment=mis, **kw)
    finally:
        tca_mod._continuation, tca_mod.exact_transfers = cont, xfer
    return got, res


def _same(a, b):
    for u, v in zip(a, b):
        assert np.array_equal(np.asarray(u), np.asarray(v), equal_nan=True)


@pytest.mark.parametrize("name", ["face-milled", "crowned"])
@pytest.mark.parametrize("mis", range(len(MISALIGNMENTS)))
def test_compiled_stages_equal_python_orchestration(pairs, name, mis):
    pinion, gear, kin, kw = pairs[name]
    got, res = _captured(pinion, gear, kin, kw, MISALIGNMENTS[mis])
    a, k = got["cont"]
    prob = a[0]
    assert prob._jets is not None
    compiled = tca_mod._continuation(*a, **k)
    python = tca_mod._continuation(_PythonPath(prob), *a[1:], **k)
    assert len(compiled[0]) >= 3
    _same(compiled[:3], python[:3])
    assert compiled[3] == python[3]
    # perturbed mean points and tangents: the same nodes (or the same failures) either way
    rng = np.random.default_rng(mis)
    for _ in range(4):
        xm = a[1] + rng.normal(0.0, 1e-3, 5)
        xp = a[2] * (1.0 + rng.normal(0.0, 0.05, 5))
        b = (prob, xm, xp) + a[3:]
        compiled = tca_mod._continuation(*b, **k)
        python = tca_mod._continuation(_PythonPath(prob), *b[1:], **k)
        _same(compiled[:3], python[:3])
        assert compiled[3] == python[3]
    # the transfer points: the whole iteration in one call against the batched Python iteration
    a, k = got["xfer"]
    assert k.get("te_frame") is not None and len(res.transfer_phi1) >= 1
    compiled = exact_transfers(*a, **k)
    python = exact_transfers(*a, **{**k, "te_frame": None})
    _same(compiled, python)
    _same(compiled, (res.transfer_phi1, res.transfer_te))
    assert np.all(np.isfinite(compiled[1]))


def test_transfer_with_edge_contact_is_compiled(pairs):
    """The face-milled pair's transfer hands the contact over to an edge contact: the compiled call solves it too."""
    pinion, gear, kin, kw = pairs["face-milled"]
    got, _ = _captured(pinion, gear, kin, kw, None)
    a, _ = got["xfer"]
    prob, sel, kinds = a[0], a[2], a[5]
    i = np.flatnonzero(sel[:-1] != sel[1:])
    ka, kb = kinds[i, sel[i]], kinds[i + 1, sel[i + 1]]
    assert isinstance(prob, ContactProblem) and (np.any(ka >= 0) or np.any(kb >= 0))
    assert _compiled(prob, ka, kb, 1e-10, (1, 0.0, 0.0), 40) is not None
