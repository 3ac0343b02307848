"""TCAResult.plot: TE panel and projected-tooth panels with outlines, contact path and ellipses."""

import numpy as np

from spiralbevel.meshing.tca_result import ARCSEC

from spiralbevel.meshing.contact_surface import NormalDeviation, quadratic_crowning
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_surfaces import conjugate_logspiral_pair
from spiralbevel.viz.tca_plot import project_axial_radial


def test_plot_draws_all_panels(tmp_path):
    pair = conjugate_logspiral_pair()
    kin = BevelPairKinematics(pair.shaft_angle, pair.z1, pair.z2)
    crowned = NormalDeviation(pair.pinion, quadratic_crowning(pair.pinion.reference_params, (0.5, 0.0, 5.0)))
    res = solve_tca(crowned, pair.gear, kin)
    fig = res.plot(outline1=pair.pinion.grid(), outline2=pair.gear.grid())
    ax_te, ax1, ax2 = fig.axes[:3]
    # TE panel: one curve per pair + the envelope through the exact transfer points, in arcsec
    env = ax_te.lines[len(res.pairs)]
    x = np.r_[res.phi1 - res.phi1_mean, res.transfer_phi1 - res.phi1_mean]
    y = np.r_[res.te_arcsec, res.transfer_te / ARCSEC]
    o = np.argsort(x, kind="stable")
    np.testing.assert_allclose(env.get_ydata(), y[o])
    # tooth panels: 4 boundary lines, the contact path, ellipses
    path = project_axial_radial(res.contact_point1)
    ok = res.status <= 1
    drawn = ax1.lines[4]
    np.testing.assert_allclose(drawn.get_xdata(), path[ok, 0])
    assert len(ax1.lines) > 6 and len(ax2.lines) > 6
    fig.savefig(tmp_path / "tca.png", dpi=60)
    assert (tmp_path / "tca.png").stat().st_size > 1000


def test_projection():
    np.testing.assert_allclose(project_axial_radial([3.0, 4.0, 7.0]), [7.0, 5.0])
