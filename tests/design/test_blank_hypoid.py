"""ISO 23509 Method 1 (Gleason) hypoid blank.

Verified against published values (ISO 23509:2016 Annex F.3, Sample 2, = ANSI/AGMA ISO 23509-B17; the figures are
given to three decimals): u, Rm1, Rm2, beta_m1, beta_m2, dm1, dm2, zeta_m, zeta_mp, ap, alpha_lim, alpha_nD,
alpha_nC, Re2, Ri2, mmn, hmw, c, ham1, ham2, hfm1, hfm2, delta_a1, delta_f1, delta_a2, delta_f2 — lengths within
±0.003 mm, angles within ±0.002° (the published rounding, 0.0005, plus the standard's loose stopping rule
|rc0/rho_lim − 1| <= 1e-4 of its iteration; the largest deviation found is Rm1, 0.0022 mm).

Verified only by a second, independent computation: the pitch point (delta1, beta_m2, Rm1, zeta_m, t_zm1, t_zm2)
by a vector model of two cones touching at one point with the relative velocity along the tooth trace
(:func:`_pitch_point_model`); the pinion face and root cones (delta_a1, delta_f1, t_zF1, t_zR1) by the 3-D distance
of skew cones, which must equal the clearance; the zero-offset limit of the pitch cones against Method 0 over several
designs; the
pinion face angle at vanishing offset against uniform clearance. Not verified by either: the pinion face width,
heel and toe spiral angles, the whole depth h_t1 and the thickness of a hypoid (the standard's formulas, no published
figure at hand);
the root/face-plane auxiliary angle φ for Σ != 90° (Sample 2 has Σ = 90°, where φ = 0).
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq
from typer.testing import CliRunner

from spiralbevel.cli import app
from spiralbevel.design.blank import BlankInput, compute_blank
from spiralbevel.design.blank_hypoid import hypoid_pitch_cone
from _hypoid_sample2 import SAMPLE2, SAMPLE2_TOML

R = math.radians
# ISO 23509 Annex F.3 Sample 2, published (subset): lengths mm, angles deg
PUBLISHED_LENGTHS = dict(Rm1=73.519, Rm2=76.337, dm1=53.383, dm2=141.877, ap=15.075, Re2=91.468, Ri2=61.468,
                         mmn=2.640, hmw=5.280, c=0.660, ham1=3.432, hfm1=2.508, ham2=1.848, hfm2=4.092)
PUBLISHED_ANGLES = dict(beta_m1=49.998, beta_m2=38.609, zeta_m=10.603, zeta_mp=11.390, alpha_lim=-2.253,
                        alpha_nD=17.747, alpha_nC=22.253, delta_a2=69.323, delta_f2=64.324, delta_a1=25.232,
                        delta_f1=20.303)
LEN_TOL, ANG_TOL = 0.003, 0.002  # mm, deg (see the module docstring)


@pytest.fixture(scope="module")
def sample2():
    with pytest.warns(Warning):  # b2 = 30 mm > 0.3*Re2: the face width warning of the standard's own sample
        return compute_blank(BlankInput(**SAMPLE2))


def test_sample2_published_figures(sample2):
    d = sample2.to_dict(degrees=True)
    assert d["u"] == pytest.approx(3.231, abs=5e-4)
    for k, v in PUBLISHED_LENGTHS.items():
        assert d[k] == pytest.approx(v, abs=LEN_TOL), k
    for k, v in PUBLISHED_ANGLES.items():
        assert d[k] == pytest.approx(v, abs=ANG_TOL), k
    assert d["rho_lim"] == pytest.approx(63.5, rel=1e-12)  # the iteration's target: rho_lim = rc0
    assert d["zeta_mp"] == pytest.approx(d["beta_m1"] - d["beta_m2"], abs=1e-12)


def _pitch_point_model(a, rmpt2, delta2, u, beta_m1):
    """Pitch point of two cones (wheel axis z, pinion axis along x at y = a, z = 0) touching at P = (R cos φ,
    R sin φ, zP): the wheel normal at P must meet the pinion axis, and the tooth trace (the relative velocity of the
    two pitch cones at P, which lies in their common tangent plane) makes beta_m1 with the pinion generator.
    Returns delta1, beta_m2, Rm1, φ (= zeta_m), t_zm1 = x_P and t_zm2 = −zP."""

    def at(phi):
        sp, cp = math.sin(phi), math.cos(phi)
        d1 = math.asin(math.cos(delta2) * cp)  # x-component of n1 = −n2
        r1 = (a - rmpt2 * sp) * math.cos(d1) / (math.cos(delta2) * sp)  # y-component
        zp = -r1 * math.sin(delta2) / math.cos(d1)  # z-component
        p = np.array([rmpt2 * cp, rmpt2 * sp, zp])
        er2, ez, ex = np.array([cp, sp, 0.0]), np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0])
        g2 = math.sin(delta2) * er2 - math.cos(delta2) * ez
        rho = np.array([0.0, p[1] - a, zp])
        er1 = rho / np.linalg.norm(rho)
        g1 = math.sin(d1) * er1 + math.cos(d1) * ex
        t = u * np.cross(ex, p - np.array([0.0, a, 0.0])) - np.cross(ez, p)
        t /= np.linalg.norm(t)
        b1, b2 = math.acos(abs(t @ g1)), math.acos(abs(t @ g2))
        return d1, b1, b2, np.linalg.norm(rho) / math.sin(d1), p

    grid = np.linspace(1e-4, math.asin(a / rmpt2) - 1e-6, 2000)
    f = [at(x)[1] - beta_m1 for x in grid]
    i = next(j for j in range(len(grid) - 1) if f[j] * f[j + 1] < 0 and abs(f[j] - f[j + 1]) < 0.5)
    phi = brentq(lambda x: at(x)[1] - beta_m1, grid[i], grid[i + 1], xtol=1e-15)
    d1, _b1, b2, rm1, p = at(phi)
    return dict(delta1=d1, beta_m2=b2, Rm1=rm1, zeta_m=phi, tzm1=p[0], tzm2=-p[2])


@pytest.mark.parametrize("a,z1,z2,beta", [(15.0, 13, 42, 50.0), (25.0, 11, 41, 45.0), (8.0, 17, 35, 40.0)])
def test_pitch_point_by_an_independent_cone_contact_model(a, z1, z2, beta):
    inp = BlankInput(**{**SAMPLE2, "a": a, "z1": z1, "z2": z2, "beta_m": R(beta), "taper": "standard",
                        "theta_a2": None, "theta_f2": None, "b": 25.0})
    pc = hypoid_pitch_cone(a=a, z1=z1, z2=z2, shaft_angle=R(90), de2=170.0, b2=25.0, beta_m1=R(beta), rc0=63.5)
    rmpt2 = pc["Rm2"] * math.sin(pc["delta2"])
    ref = _pitch_point_model(a, rmpt2, pc["delta2"], z2 / z1, pc["beta_m1"])
    for k in ("delta1", "beta_m2"):  # the standard's closed-form chain vs the vector model: round-off only
        assert pc[k] == pytest.approx(ref[k], abs=1e-9), k
    bl = _quiet(compute_blank, inp)
    assert bl.delta1 == pytest.approx(ref["delta1"], abs=1e-9)
    assert bl.beta_m2 == pytest.approx(ref["beta_m2"], abs=1e-9)
    assert bl.zeta_m == pytest.approx(ref["zeta_m"], abs=1e-9)
    for k in ("Rm1", "tzm1", "tzm2"):
        assert getattr(bl, k) == pytest.approx(ref[k], abs=1e-7), k


def _quiet(fn, *args):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fn(*args)


DESIGNS = [  # (z1, z2, Sigma deg, de2, b2, beta deg, rc0)
    (14, 39, 90.0, 176.893, 25.4, 35.0, 114.3),
    (13, 42, 90.0, 170.0, 30.0, 50.0, 63.5),
    (17, 29, 75.0, 150.0, 22.0, 30.0, 76.2),
    (10, 37, 100.0, 200.0, 30.0, 40.0, 88.9),
]


@pytest.mark.parametrize("z1,z2,sig,de2,b2,beta,rc0", DESIGNS)
def test_zero_offset_gives_method0(z1, z2, sig, de2, b2, beta, rc0):
    """a = 0 is Method 0 exactly (the same code path, bit for bit); as a -> 0 the Method 1 pitch cones tend to the
    Method 0 cones linearly in a (delta1 + delta2 -> Sigma, beta_m1 = beta_m2, alpha_lim -> 0)."""
    base = dict(z1=z1, z2=z2, shaft_angle=R(sig), de2=de2, b=b2, beta_m=R(beta), rc0=rc0, taper="standard")
    m0 = _quiet(compute_blank, BlankInput(**base))
    z = _quiet(compute_blank, BlankInput(**base, a=0.0))
    assert z.to_dict() == m0.to_dict()
    assert (z.zeta_m, z.zeta_mp, z.ap, z.alpha_lim, z.c_be2) == (0.0, 0.0, 0.0, 0.0, 0.5)
    errs = []
    for a in (1e-2, 1e-3):
        pc = hypoid_pitch_cone(a=a, z1=z1, z2=z2, shaft_angle=R(sig), de2=de2, b2=b2, beta_m1=R(beta), rc0=rc0)
        errs.append(max(abs(pc["delta1"] - m0.delta1), abs(pc["delta1"] + pc["delta2"] - R(sig)),
                        abs(pc["beta_m1"] - pc["beta_m2"]), abs(pc["alpha_lim"])))
    assert errs[1] < 2e-5 and errs[0] / errs[1] == pytest.approx(10.0, rel=0.02)  # first order in a


@pytest.mark.parametrize("z1,z2,sig,de2,b2,beta,rc0", [d for d in DESIGNS if d[2] == 90.0])
def test_pinion_cones_tend_to_uniform_clearance(z1, z2, sig, de2, b2, beta, rc0):
    """At vanishing offset the pinion face cone is parallel to the wheel root cone (theta_a1 -> theta_f2) and its
    root cone to the wheel face cone (theta_f1 -> theta_a2), as in Method 0."""
    bl = _quiet(compute_blank, BlankInput(z1=z1, z2=z2, shaft_angle=R(sig), de2=de2, b=b2, beta_m=R(beta), rc0=rc0,
                                          taper="standard", a=1e-4))
    assert bl.theta_a1 == pytest.approx(bl.theta_f2, abs=1e-6)
    assert bl.theta_f1 == pytest.approx(bl.theta_a2, abs=1e-6)


def _min_distance_to_wheel_cone(bl, pinion_angle, pinion_apex, wheel_angle, wheel_apex):
    """Smallest signed distance (outward from the wheel) of a pinion cone (axis +x through (0, a, 0), apex at
    x = −t_z beyond the crossing point) from a wheel cone (axis z, apex at z = t_z), over pinion points within ±30 %
    of Rm1 along the generator; Nelder-Mead from 12 azimuths."""
    from scipy.optimize import minimize

    def dist(q):
        length = bl.Rm1 * (1.0 + 0.3 * math.tanh(q[0]))
        x = -pinion_apex + length * math.cos(pinion_angle)
        y = bl.a + length * math.sin(pinion_angle) * math.cos(q[1])
        z = length * math.sin(pinion_angle) * math.sin(q[1])
        return math.hypot(x, y) * math.cos(wheel_angle) + (z - wheel_apex) * math.sin(wheel_angle)

    opts = dict(xatol=1e-12, fatol=1e-15, maxiter=8000)
    return min(minimize(dist, [0.0, t], method="Nelder-Mead", options=opts).fun
               for t in np.linspace(-math.pi, math.pi, 12))


@pytest.mark.parametrize("kw", [{}, {"a": 25.0}, {"a": -15.0}, {"taper": "standard", "theta_a2": None,
                                                                "theta_f2": None}])
def test_pinion_face_and_root_cones_clear_the_wheel_cones_by_c(kw):
    """Independent check of delta_a1, t_zF1, delta_f1, t_zR1 (and so zeta_R, zeta_o): in 3-D the pinion face cone
    touches the wheel root cone offset by the clearance c, and the pinion root cone the wheel face cone, i.e. the
    smallest distance between the skew cones is c (to the optimizer's 1e-12 mm)."""
    bl = _quiet(compute_blank, BlankInput(**{**SAMPLE2, **kw}))
    face = _min_distance_to_wheel_cone(bl, bl.delta_a1, bl.tzF1, bl.delta_f2, bl.tzR2)
    root = _min_distance_to_wheel_cone(bl, bl.delta_f1, bl.tzR1, bl.delta_a2, bl.tzF2)
    assert face == pytest.approx(bl.c, abs=1e-10) and root == pytest.approx(bl.c, abs=1e-10)


def test_offset_sign_follows_iso_b3():
    """a > 0 (pinion offset in the wheel's hand of spiral): beta_m1 > beta_m2 and alpha_lim < 0; a < 0 the reverse."""
    kw = dict(z1=13, z2=42, shaft_angle=R(90), de2=170.0, b2=30.0, beta_m1=R(45), rc0=63.5)
    pos, neg = hypoid_pitch_cone(a=15.0, **kw), hypoid_pitch_cone(a=-15.0, **kw)
    assert pos["beta_m1"] > pos["beta_m2"] and pos["alpha_lim"] < 0.0
    assert neg["beta_m1"] < neg["beta_m2"] and neg["alpha_lim"] > 0.0




def test_cli_blank_shows_the_hypoid_sheet(tmp_path):
    import json

    f = tmp_path / "hypoid.toml"
    f.write_text(SAMPLE2_TOML)
    runner = CliRunner()
    res = runner.invoke(app, ["blank", str(f), "--json"])
    assert res.exit_code == 0, res.output
    sheet = json.loads(res.stdout[res.stdout.index("{"):])
    assert "Method 1" in sheet["method"]
    assert sheet["pair"]["zeta_mp"] == pytest.approx(PUBLISHED_ANGLES["zeta_mp"], abs=ANG_TOL)
    assert sheet["pinion"]["delta_a1"] == pytest.approx(PUBLISHED_ANGLES["delta_a1"], abs=ANG_TOL)
    assert sheet["pair"]["alpha_nD"] == pytest.approx(PUBLISHED_ANGLES["alpha_nD"], abs=ANG_TOL)  # f_alim = 1 read
    # `spiralbevel run` develops the hypoid pair: tests/gearset/test_run_hypoid.py


def test_rate_on_a_hypoid_asks_for_the_hypoid_factor(tmp_path):
    # the ISO 10300 hypoid rating takes Z_Hyp as given (tests/rating/test_hypoid_sample2.py): without it, a clear
    # error naming the key, not a spiral bevel rating that ignores the offset
    f = tmp_path / "hypoid.toml"
    rating = ("\n[rating]\npinion_torque = 300.0\npinion_speed = 1200.0\nsigma_Hlim = 1500.0\nsigma_Flim = 480.0\n"
              "oil_viscosity = 150.0\naccuracy_grade = 6\n")
    f.write_text(SAMPLE2_TOML + rating)
    res = CliRunner().invoke(app, ["rate", str(f)])
    assert res.exit_code == 2, res.output
    assert "rating.hypoid_factor" in " ".join(res.output.split())
    assert "Traceback" not in res.output
    f.write_text(SAMPLE2_TOML + rating + "hypoid_factor = 0.95\n")
    res = CliRunner().invoke(app, ["rate", str(f), "--json"])
    assert res.exit_code == 0, res.output
    assert '"Z_Hyp": 0.95' in res.output


def test_random_hypoid_data_give_a_sheet_or_a_design_error():
    """Bad hypoid data never raise a bare exception or give a non-finite figure (60 random designs, both offset
    signs, Sigma 75-100 deg, all computed tapers)."""
    from spiralbevel.errors import DesignError

    rng = np.random.default_rng(7)
    ok = 0
    for _ in range(60):
        z1 = int(rng.integers(5, 21))
        de2 = float(rng.uniform(80.0, 400.0))
        kw = dict(z1=z1, z2=int(rng.integers(z1, 61)), de2=de2, b=float(rng.uniform(0.05, 0.45)) * de2 / 2,
                  beta_m=R(float(rng.uniform(5.0, 60.0))), rc0=float(rng.uniform(20.0, 300.0)),
                  a=float(rng.uniform(-0.49, 0.49)) * de2, shaft_angle=R(float(rng.choice([75.0, 90.0, 100.0]))),
                  taper=str(rng.choice(["standard", "duplex", "trl", "uniform"])))
        try:
            bl = _quiet(compute_blank, BlankInput(**kw))
        except DesignError as err:
            assert err.problems and all(p.field for p in err.problems)
            continue
        ok += 1
        for k, v in bl.to_dict().items():
            assert not isinstance(v, float) or math.isfinite(v) or k in ("tzR1", "tzR2", "dvn2", "hlim2"), (k, kw)
    assert ok >= 20  # most random designs are valid hypoids


@pytest.mark.parametrize("method,offset,ok", [(1, 15.0, True), (0, 15.0, False), (1, 0.0, False), (2, 15.0, False),
                                              (0, 0.0, True)])
def test_blank_method_key_must_fit_the_offset(tmp_path, method, offset, ok):
    f = tmp_path / "m.toml"
    f.write_text(SAMPLE2_TOML.replace("hypoid_offset = 15.0", f"hypoid_offset = {offset}\nblank_method = {method}"))
    res = CliRunner().invoke(app, ["blank", str(f)])
    assert res.exit_code == (0 if ok else 2), res.output
    if not ok:
        assert "gear_set.blank_method" in res.output and "Traceback" not in res.output
