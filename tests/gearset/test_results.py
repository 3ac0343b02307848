"""Result objects of GearSet: concise reprs, HTML for notebooks, plots as matplotlib Figures, one unit convention."""

import warnings

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.figure import Figure

import spiralbevel as sb


@pytest.fixture(scope="module")
def gs():
    g = sb.GearSet.from_design("aviation_23x65_facemilled")
    spec = g.design.model_copy(update={"output": g.design.output.model_copy(update={"grid": (9, 5)}),
                                       "tca": g.design.tca.model_copy(update={"positions": 11})})
    return sb.GearSet(spec)


def _concise(obj):
    text = repr(obj)
    assert "array(" not in text and "np.float64" not in text and "np.int64" not in text, text
    assert len(text) < 600, text
    html = obj._repr_html_()
    assert html.startswith("<table>") and html.endswith("</table>")


def test_results_repr_html_and_plot(gs):
    _concise(gs)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        results = [gs.tca("drive"), gs.sensitivity(), gs.easeoff(), gs.machine_summary(), gs.measurement_grid()]
    for r in results:
        _concise(r)
        fig = r.plot()
        assert isinstance(fig, Figure) and fig.axes
        plt.close(fig)


def test_tca_units_and_summary(gs):
    t = gs.tca("drive")
    res = t.result
    # the result object speaks arcsec and degrees; the solver's result rad (one conversion, checked here)
    assert t.peak_to_peak_arcsec == pytest.approx(res.peak_to_peak * 180 / np.pi * 3600, rel=1e-12)
    fin = np.isfinite(res.te)
    assert np.allclose(t.pinion_rotation_deg, np.degrees(res.phi1[fin]), rtol=0, atol=1e-12)
    assert "np.int64" not in res.summary() and "array(" not in repr(res) and len(repr(res)) < 400
    # a misalignment given in mm and degrees is the same as the Misalignment object in mm and rad
    a = gs.tca("drive", misalignment={"shaft_angle": 0.05}).peak_to_peak_arcsec
    b = gs.tca("drive", misalignment=sb.Misalignment(shaft_angle=np.radians(0.05))).peak_to_peak_arcsec
    assert a == b


def test_logspiral_methods_say_why_they_are_missing():
    g = sb.GearSet.from_design("aviation_23x65_logspiral")
    with pytest.raises(sb.DesignError, match="flank.kind.*log-spiral.*needs a face-milled design"):
        g.machine_summary()
    t = g.tca("convex-concave")
    _concise(t)
    assert t.to_dict()["max_abs_transmission_error_arcsec"] < 1e-3   # exactly conjugate: line contact, zero TE
