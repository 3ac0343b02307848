"""The edge stage of TCA in one compiled call (``_core.tca_edge_stage.edge_stage_run``) against its Python statement
in ``meshing/tca_edge.edge_stage`` (run where the compiled arguments are withheld): the same edge contacts, TE and
labels, bit for bit, on the inputs that ``solve_tca`` hands the stage for the face-milled pair (aligned and
misaligned: more edge contacts, corners) and for the two pairs whose gear flank folds past a limit line of generation.
The Python statement solves each batch with the edge Newton and evaluates the limit-line tests, margins and TE by
numpy; the compiled stage fuses them, so the test checks the fused candidates, corner rounds and march against the
separate steps."""

import numpy as np
import pytest
from _interference_pair import coast_pair as interference_pair
from _limit_line_pair import coast_pair as limit_line_pair
from _meshing_helpers import seed001_synthesized_pair

from spiralbevel._core import tca_edge_stage as kst
from spiralbevel._core.tca_corner_screen import N_SAMPLES
from spiralbevel.meshing import tca as tca_mod
from spiralbevel.meshing import tca_edge as te_mod
from spiralbevel.meshing.misalignment import Misalignment
from spiralbevel.meshing.tca import solve_tca

_PAIRS = {"seed001": seed001_synthesized_pair, "folded": interference_pair, "limit_line": limit_line_pair}
_MIS = Misalignment(pinion_axial=0.05, gear_axial=-0.03, offset=0.04, shaft_angle=0.0)


def _stage_inputs(name, mis, n, monkeypatch):
    """The arguments of every ``edge_stage`` call of one TCA of a named pair."""
    c1, c2, kin = _PAIRS[name]()
    calls = []
    stage = te_mod.edge_stage

    def record(*args, **kw):
        calls.append((args, kw))
        return stage(*args, **kw)

    monkeypatch.setattr(tca_mod, "edge_stage", record)
    solve_tca(c1, c2, kin, misalignment=mis, n_positions=n, start=np.r_[c1.reference_params, c2.reference_params, 0])
    monkeypatch.undo()
    return calls


@pytest.mark.parametrize("name, mis, n", [("seed001", None, 41), ("seed001", _MIS, 41), ("folded", None, 41),
                                          ("limit_line", None, 81)])
def test_compiled_stage_equals_its_python_statement(name, mis, n, monkeypatch):
    calls = _stage_inputs(name, mis, n, monkeypatch)
    assert calls
    runs = []
    for args, kw in calls:
        got = te_mod.edge_stage(*args, **kw)
        monkeypatch.setattr(te_mod, "compiled_args", lambda prob: None)
        ref = te_mod.edge_stage(*args, **kw)
        monkeypatch.undo()
        assert np.array_equal(got[0], ref[0], equal_nan=True)
        assert np.array_equal(got[1], ref[1], equal_nan=True)
        assert got[2] == ref[2]
        runs.append(got)
    # the stage is exercised: edge contacts found, and on the misaligned pair a march over several positions
    assert sum(len(r[2]) for r in runs) >= (10 if mis is not None else 1)


def test_stage_stops_for_the_junction_samples_and_runs_again(monkeypatch):
    """Where the samples of the pinion's fillet junction (the corner proof) are not computed yet, the compiled stage
    stops at the first batch that needs them and is run again with them: the same result as with them given."""
    calls = _stage_inputs("seed001", _MIS, 41, monkeypatch)
    args, kw = calls[0]
    prob = args[0]
    ref = te_mod.edge_stage(*args, **kw)
    assert prob.__dict__.get("_junction") is not None and len(prob._junction) == N_SAMPLES
    prob.__dict__.pop("_junction")
    prob.pinion.__dict__.pop("_junction_src", None)
    runs = []
    run = kst.edge_stage_run

    def count(*a):
        run(*a)
        runs.append(int(a[-1][0]))

    monkeypatch.setattr(kst, "edge_stage_run", count)
    got = te_mod.edge_stage(*args, **kw)
    assert runs == [1, 0]
    assert np.array_equal(got[0], ref[0], equal_nan=True) and np.array_equal(got[1], ref[1], equal_nan=True)
    assert got[2] == ref[2]
