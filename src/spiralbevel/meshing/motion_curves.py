"""Motion curves (functions of transmission errors): parabolic, quartic, and the predesigned fourth-order combined
motion curve (CMC) of seed 001 §2 (Eqs. (1)-(6) as decoded in docs/theory/tca.md, Eqs. (T1)-(T4)).

Units: the abscissa x = phi1 - phi10 is the pinion rotation from the mean contact point in rad; Delta phi2 is the
gear's transmission error in rad (reports convert to arcsec with :data:`ARCSEC`). Sign: the TE convention of
:class:`~spiralbevel.meshing.tca_result.TCAResult` (positive = gear ahead); a crowned pair has a2 < 0 and the pair in
contact is the upper envelope of the pair curves.

CMC formation (seed 001 §2.2, docs/theory/tca.md, Eqs. (T1)-(T4); Table 3 of the seed is inconsistent and is not used):

* Step 1: least-squares quartic a2 x^2 + a3 x^3 + a4 x^4 through the designer's control points A_i (Eq. 3);
* Step 2: its two non-zero roots B1(b1, 0), B3(b3, 0), b1 < 0 < b3, and the parabola through B1, B2(0, b2), B3 in
  the general form b2 (x - b1)(x - b3) / (b1 b3) (Eq. 4; the printed b2 - (b2/b1^2) x^2 is the case b3 = -b1);
* Step 3: CMC = parabola outside [b1, b3], quartic inside (Eq. 5);
* Step 4: shift down by its maximum: Delta phi2 = CMC - max CMC (Eq. 6).

Continuity: C0 holds at B1 and B3 by construction (both pieces vanish there). The parabola has slopes
p'(b1) = -p'(b3) = b2 (b1 - b3)/(b1 b3), so one b2 gives C1 at both points only if q'(b1) = -q'(b3) (e.g. a symmetric
quartic, a3 = 0, where b2 = a2 b1^2 = -a2^2/a4). In general b2 minimises the sum of the squared slope jumps;
:meth:`CombinedMotionCurve.continuity` reports the jumps.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..errors import DesignError
from .tca_result import ARCSEC

__all__ = [
    "ARCSEC",
    "parabolic_te",
    "quartic_te",
    "fit_quartic",
    "quartic_roots",
    "parabola_through",
    "CombinedMotionCurve",
    "seed001_control_points",
    "seed001_cmc",
    "TEComparison",
    "compare_te",
]


def parabolic_te(x, a2):
    """Delta phi2 = a2 x^2 (seed 001 Eq. (2)); x rad, a2 1/rad, result rad."""
    x = np.asarray(x, float)
    return a2 * x**2


def quartic_te(x, a):
    """Delta phi2 = a2 x^2 + a3 x^3 + a4 x^4 (seed 001 Eq. (3)); ``a = (a2, a3, a4)``, x rad, result rad."""
    a2, a3, a4 = a
    x = np.asarray(x, float)
    return x**2 * (a2 + x * (a3 + x * a4))


def _quartic_slope(x, a):
    a2, a3, a4 = a
    return x * (2 * a2 + x * (3 * a3 + 4 * a4 * x))


def fit_quartic(x, y):
    """Step 1: least-squares (a2, a3, a4) of the quartic through control points (x rad, y rad)."""
    x = np.asarray(x, float).reshape(-1)
    y = np.asarray(y, float).reshape(-1)
    if x.size != y.size or x.size < 3 or not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        raise DesignError.single("control points", (x.size, y.size), "at least 3 finite (x, y) pairs", "rad")
    A = np.stack([x**2, x**3, x**4], -1)
    return tuple(float(v) for v in np.linalg.lstsq(A, y, rcond=None)[0])


def quartic_roots(a):
    """Step 2: the non-zero roots b1 < 0 < b3 (rad) of the quartic, i.e. of a2 + a3 x + a4 x^2."""
    a2, a3, a4 = a
    disc = a3 * a3 - 4 * a2 * a4
    if a4 == 0 or disc <= 0:
        raise DesignError.single("quartic", a, "two real non-zero roots b1 < 0 < b3", "rad",
                                 "the quartic must cross the abscissa on both sides of the mean point")
    s = np.sqrt(disc)
    r = sorted([(-a3 - s) / (2 * a4), (-a3 + s) / (2 * a4)])
    if not r[0] < 0 < r[1]:
        raise DesignError.single("quartic roots", r, "b1 < 0 < b3", "rad", "roots on one side of the mean point")
    return float(r[0]), float(r[1])


def parabola_through(x, b1, b2, b3):
    """Parabola through B1(b1, 0), B2(0, b2), B3(b3, 0): b2 (x - b1)(x - b3) / (b1 b3) (docs/theory/tca.md, Eq.
    (T3))."""
    x = np.asarray(x, float)
    return b2 * (x - b1) * (x - b3) / (b1 * b3)


@dataclass(frozen=True)
class CombinedMotionCurve:
    """The final CMC of seed 001 Eq. (6).

    Attributes
    ----------
    a : (3,) float
        (a2 rad^-1, a3 rad^-2, a4 rad^-3) of the quartic.
    b1, b3 : float, rad
        Roots of the quartic (B1, B3).
    b2 : float, rad
        Ordinate of B2.
    shift : float, rad
        Delta phi2 max, the maximum of Eq. (5).
    """

    a: tuple
    b1: float
    b2: float
    b3: float
    shift: float

    @classmethod
    def from_quartic(cls, a, b2=None) -> "CombinedMotionCurve":
        """Steps 2-4 from quartic coefficients; b2 by least squares on the slope jumps when omitted."""
        a = tuple(float(v) for v in a)
        b1, b3 = quartic_roots(a)
        if b2 is None:
            s = (b1 - b3) / (b1 * b3)  # p'(b1) = b2 s, p'(b3) = -b2 s
            b2 = (_quartic_slope(b1, a) - _quartic_slope(b3, a)) / (2 * s)
        if not b2 > 0:
            raise DesignError.single("b2", b2, "> 0", "rad", "the parabola must open downward so that the CMC "
                                     "has a maximum (choose control points with a2 > 0 and a4 < 0)")
        raw = cls(a, b1, float(b2), b3, 0.0)
        # maximum of Eq. (5): the parabola's max on the outer pieces is at its ends (b1, b3: value 0) unless its
        # vertex lies outside [b1, b3]; the quartic's max from its stationary points inside
        cand = [b1, b3, 0.0]
        st = np.roots([4 * a[2], 3 * a[1], 2 * a[0]])
        cand += [float(r.real) for r in st if abs(r.imag) < 1e-14 and b1 <= r.real <= b3]
        vertex = 0.5 * (b1 + b3)
        if not b1 <= vertex <= b3:
            cand.append(vertex)
        shift = float(max(raw.raw(np.array(cand))))
        return replace(raw, shift=shift)

    @classmethod
    def from_control_points(cls, x, y, b2=None) -> "CombinedMotionCurve":
        """Steps 1-4 from the designer's control points (x rad, y rad)."""
        return cls.from_quartic(fit_quartic(x, y), b2)

    def raw(self, x):
        """Eq. (5), before the shift, rad."""
        x = np.asarray(x, float)
        inner = (x >= self.b1) & (x <= self.b3)
        return np.where(inner, quartic_te(x, self.a), parabola_through(x, self.b1, self.b2, self.b3))

    def __call__(self, x):
        """Eq. (6): Delta phi2(x) = CMC(x) - Delta phi2 max, rad (x rad)."""
        return self.raw(x) - self.shift

    def slope(self, x):
        """d Delta phi2 / dx (-)."""
        x = np.asarray(x, float)
        inner = (x >= self.b1) & (x <= self.b3)
        par = self.b2 * (2 * x - self.b1 - self.b3) / (self.b1 * self.b3)
        return np.where(inner, _quartic_slope(x, self.a), par)

    def continuity(self) -> dict:
        """Jumps (parabola minus quartic) of value (rad) and slope (-) at B1 and B3."""
        out = {}
        for name, b in (("b1", self.b1), ("b3", self.b3)):
            out[f"c0_{name}"] = float(parabola_through(b, self.b1, self.b2, self.b3) - quartic_te(b, self.a))
            par = self.b2 * (2 * b - self.b1 - self.b3) / (self.b1 * self.b3)
            out[f"c1_{name}"] = float(par - _quartic_slope(b, self.a))
        return out

    def envelope(self, x, period, copies=2):
        """Upper envelope max_k Delta phi2(x - k period), k = -copies..copies: the TE of meshing pairs, rad."""
        x = np.asarray(x, float)
        k = np.arange(-copies, copies + 1)
        return np.max(self(x[..., None] - k * period), axis=-1)

    def depth(self, period, samples=4001) -> float:
        """Peak-to-peak of the envelope over one mesh cycle (the magnitude of the FTE), rad.

        The extremes are located on a grid and refined: the minimum sits at a transfer point (two pair curves
        cross, solved by brentq) or at a smooth local minimum, the maximum at a smooth local maximum.
        """
        from scipy.optimize import brentq, minimize_scalar

        P = float(period)
        x = np.linspace(-0.6 * P, 0.6 * P, samples)  # a little more than one period (the envelope is periodic)
        k = np.arange(-2, 3)
        V = self(x[:, None] - k * P)
        E = V.max(axis=1)
        out = []
        for sign in (1.0, -1.0):  # max, then min
            i = int(np.clip(np.argmax(sign * E), 1, samples - 2))
            ka, kb = np.argmax(V[i - 1]), np.argmax(V[i + 1])
            lo, hi = x[i - 1], x[i + 1]
            if ka != kb:
                def g(t, ka=ka, kb=kb):
                    return self(t - k[ka] * P) - self(t - k[kb] * P)
                t = brentq(g, lo, hi, xtol=1e-16) if g(lo) * g(hi) < 0 else x[i]
                out.append(float(self(t - k[ka] * P)))
            else:
                r = minimize_scalar(lambda t, sign=sign, ka=ka: -sign * float(self(t - k[ka] * P)), bounds=(lo, hi),
                                    method="bounded", options={"xatol": 1e-14})
                out.append(max(sign * float(self(r.x - k[ka] * P)), sign * float(E[i])) * sign)
        return out[0] - out[1]

    def scaled(self, factor: float) -> "CombinedMotionCurve":
        """All ordinates times ``factor`` > 0 (roots unchanged)."""
        return CombinedMotionCurve(tuple(factor * v for v in self.a), self.b1, factor * self.b2, self.b3,
                                   factor * self.shift)


def seed001_control_points(z1=23, hump=0.25, skew=0.15, n=10):
    """Step 1 control points A_1..A_n of the seed-001 example (shape only; scaled by :func:`seed001_cmc`).

    The designer intent: TE zero at the mean point, humps of unit height at x = +-hump * T (T = 2 pi / z1), falling
    off beyond, with a slight asymmetry ``skew`` (as the seed's non-zero a3 suggests); points evenly spaced over
    [-1.4, 1.4] hump positions.

    Returns
    -------
    x, y : (n,) float, rad and - (relative ordinates)
    """
    T = 2 * np.pi / z1
    xh = hump * T
    u = np.linspace(-1.4, 1.4, n)
    y = (2 * u**2 - u**4) * (1 + skew * u)
    return u * xh, y


def seed001_cmc(magnitude=3.0 * ARCSEC, z1=23, **kw) -> CombinedMotionCurve:
    """The regenerated CMC of seed 001 §5: Steps 1-4 on :func:`seed001_control_points`, scaled so that the depth of
    the TE envelope over one mesh cycle (2 pi / z1) equals ``magnitude`` (rad; 3 arcsec,
    docs/theory/example.md#table-2)."""
    x, y = seed001_control_points(z1, **kw)
    c = CombinedMotionCurve.from_control_points(x, y)
    return c.scaled(magnitude / c.depth(2 * np.pi / z1))


@dataclass(frozen=True)
class TEComparison:
    """Deviation of a TCA transmission error from a predesigned curve.

    Attributes
    ----------
    max_deviation : float, rad
    depth : float, rad
        Peak-to-peak of the predesigned envelope over the compared positions.
    relative : float
        max_deviation / depth.
    deviation : (n,) float, rad
    """

    max_deviation: float
    depth: float
    relative: float
    deviation: np.ndarray

    @property
    def max_deviation_arcsec(self) -> float:
        return self.max_deviation / ARCSEC


def compare_te(phi1, te, curve, phi1_mean=0.0, period=None, align="max") -> TEComparison:
    """Compare a TCA TE (the contact envelope) with a predesigned curve.

    Parameters
    ----------
    phi1, te : (n,) float, rad
        Pinion positions and TE (e.g. ``result.phi1``, ``result.te``); NaN entries are ignored.
    curve : callable
        Delta phi2(x) in rad of x = phi1 - phi10 in rad (e.g. a :class:`CombinedMotionCurve`).
    period : float, rad, optional
        Mesh period 2 pi / z1: the curve's upper envelope over neighbouring pairs is compared (if ``curve`` has
        ``envelope``); otherwise the curve itself.
    align : {"max", "none"}
        "max" shifts both so that their maxima over the compared positions are 0 (seed 001 Eq. (6)).
    """
    phi1 = np.asarray(phi1, float)
    te = np.asarray(te, float)
    ok = np.isfinite(te)
    if not np.any(ok):
        raise DesignError.single("te", "all NaN", "some finite values", "rad")
    x = phi1 - phi1_mean
    ref = curve.envelope(x, period) if (period is not None and hasattr(curve, "envelope")) else curve(x)
    a, b = te[ok], np.asarray(ref, float)[ok]
    if align == "max":
        a, b = a - a.max(), b - b.max()
    elif align != "none":
        raise DesignError.single("align", align, "'max' or 'none'", "-")
    dev = np.full(te.shape, np.nan)
    dev[ok] = a - b
    depth = float(b.max() - b.min())
    m = float(np.max(np.abs(a - b)))
    return TEComparison(m, depth, m / depth if depth > 0 else float("inf"), dev)
