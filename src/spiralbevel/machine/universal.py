"""Universal generator: a cradle-type hypoid generator with cutter tilt and swivel, blank offset, sliding base,
machine centre to back, machine root angle, ratio of roll, and the universal motions (helical, vertical and radial
motion and modified roll) as polynomials in the cradle angle. The gear may be generated or Formate (non-generated:
the flank is the cutter surface itself, the cradle locked, no roll).

Signs: docs/conventions.md "Universal generator" (pinned by tests/machine/test_universal.py); theory:
docs/theory/universal.md. With zero tilt, swivel and motions it is the face-milling generator of
``spiralbevel.generation`` (MachineSettings) in a second, independent parametrization (4x4 chain, complex-step
derivative, meshing in the member frame), and reproduces its points and normals to round-off.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

from spiralbevel._core import universal_generator as _u
from spiralbevel.conventions import Hand
from spiralbevel.errors import DesignError, GeometryError, Problem

__all__ = ["UniversalSettings", "UniversalGenerator", "UniversalPoints"]

_MIRROR = np.array([1.0, -1.0, 1.0])

_LABELS = [
    ("radial_setting", "Radial setting S_r", "mm", False),
    ("cradle_angle", "Cradle (installment) angle q", "deg", True),
    ("tilt", "Cutter tilt i", "deg", True),
    ("swivel", "Swivel j", "deg", True),
    ("machine_root_angle", "Machine root angle gamma_m", "deg", True),
    ("machine_centre_to_back", "Machine centre to back X_D", "mm", False),
    ("sliding_base", "Sliding base X_B", "mm", False),
    ("blank_offset", "Blank offset (vertical offset) E_m", "mm", False),
    ("ratio_of_roll", "Ratio of roll m_ic", "-", False),
]


@dataclass(frozen=True)
class UniversalSettings:
    """Settings of one member and side on the universal generator (canonical left-hand machine; the right-hand
    machine is its mirror image, every setting keeping its number and sign).

    Parameters
    ----------
    radial_setting : float, mm
        S_r at psi_c = 0, > 0.
    cradle_angle : float, rad
        q, from the root line (-X_m) to the ray machine centre -> cutter centre, positive toward +Y_m.
    machine_root_angle : float, rad
        gamma_m, 0 < gamma_m < pi/2 (a Formate gear is cut at its root angle).
    machine_centre_to_back : float, mm
        X_D, positive moves the work along its axis away from the machine centre.
    sliding_base : float, mm
        X_B at psi_c = 0, positive moves the work along -Z_m (deeper into the cut).
    blank_offset : float, mm
        E_m at psi_c = 0 (vertical offset), positive away from the side of the root line on which the cutter centre
        lies.
    ratio_of_roll : float
        m_ic = d psi_i/d psi_c at psi_c = 0, > 0 (unused on a Formate gear).
    tilt : float, rad
        i, cutter tilt: the cutter axis turns by i about the swivel line d (right-hand rule), |i| < pi/2.
    swivel : float, rad
        j, direction of the swivel line d = e(pi - q + psi_c + j) in the cradle plane, measured from the ray machine
        centre -> cutter centre, positive about +Z_m; -pi..pi.
    modified_roll : tuple of float
        (2C, 6D, 24E, 120F): psi_i = m_ic (psi_c - 2C psi_c^2/2! - ... - 120F psi_c^5/5!), as ``MachineSettings``.
    helical_motion : tuple of float, mm
        (h1, h2, ...): X_B(psi_c) = X_B + h1 psi_c + h2 psi_c^2 + ... (sliding base moving with the cradle).
    vertical_motion : tuple of float, mm
        (v1, v2, ...): E_m(psi_c) = E_m + v1 psi_c + v2 psi_c^2 + ... (= ``MachineSettings.blank_offset_poly``).
    radial_motion : tuple of float, mm
        (r1, r2, ...): S_r(psi_c) = S_r + r1 psi_c + r2 psi_c^2 + ...
    generated : bool
        False for a Formate (non-generated) member: the flank is the cutter surface at psi_c = 0.
    """

    radial_setting: float
    cradle_angle: float
    machine_root_angle: float
    machine_centre_to_back: float = 0.0
    sliding_base: float = 0.0
    blank_offset: float = 0.0
    ratio_of_roll: float = 1.0
    tilt: float = 0.0
    swivel: float = 0.0
    modified_roll: tuple = field(default=())
    helical_motion: tuple = field(default=())
    vertical_motion: tuple = field(default=())
    radial_motion: tuple = field(default=())
    generated: bool = True

    def __post_init__(self):
        p: list = []

        def fin(name, ok, allowed, unit):
            val = getattr(self, name)
            if isinstance(val, bool) or not (isinstance(val, (int, float)) and math.isfinite(val) and ok(val)):
                p.append(Problem(f"settings.{name}", val, allowed, unit))
            else:
                object.__setattr__(self, name, float(val))

        fin("radial_setting", lambda v: v > 0, "> 0", "mm")
        fin("cradle_angle", lambda v: -math.pi <= v <= math.pi, "-pi..pi", "rad")
        fin("machine_root_angle", lambda v: 0 < v < 0.5 * math.pi, "0 < value < pi/2", "rad")
        for name in ("machine_centre_to_back", "sliding_base", "blank_offset"):
            fin(name, lambda v: True, "finite", "mm")
        fin("ratio_of_roll", lambda v: v > 0, "> 0", "-")
        fin("tilt", lambda v: abs(v) < 0.5 * math.pi, "|value| < pi/2", "rad")
        fin("swivel", lambda v: -math.pi <= v <= math.pi, "-pi..pi", "rad")
        for name, n_max, unit in (("modified_roll", 4, "-"), ("helical_motion", 6, "mm"),
                                  ("vertical_motion", 6, "mm"), ("radial_motion", 6, "mm")):
            val = getattr(self, name)
            try:
                coeffs = tuple(float(c) for c in val)
            except (TypeError, ValueError):
                coeffs = None
            if coeffs is None or len(coeffs) > n_max or not all(math.isfinite(c) for c in coeffs):
                p.append(Problem(f"settings.{name}", val, f"up to {n_max} finite values", unit))
            else:
                object.__setattr__(self, name, coeffs)
        if not isinstance(self.generated, bool):
            p.append(Problem("settings.generated", self.generated, "true or false", "-"))
        if p:
            raise DesignError(p)

    @classmethod
    def from_machine_settings(cls, settings, tilt: float = 0.0, swivel: float = 0.0) -> "UniversalSettings":
        """The same machine as a ``MachineSettings`` (its variable offset polynomial becomes the vertical motion).

        A piecewise blank-offset table has no polynomial equivalent: ``DesignError``.
        """
        if settings.blank_offset_table:
            raise DesignError.single("settings.blank_offset_table", "table", "empty (polynomial motions only)",
                                     "mm", "the universal generator takes motions as polynomials in psi_c")
        return cls(radial_setting=settings.radial_setting, cradle_angle=settings.cradle_angle,
                   machine_root_angle=settings.machine_root_angle,
                   machine_centre_to_back=settings.machine_centre_to_back, sliding_base=settings.sliding_base,
                   blank_offset=settings.blank_offset, ratio_of_roll=settings.ratio_of_roll, tilt=tilt,
                   swivel=swivel, modified_roll=settings.modified_roll,
                   vertical_motion=settings.blank_offset_poly)

    def replace(self, **changes) -> "UniversalSettings":
        """A copy with some fields changed (validated again)."""
        d = asdict(self)
        d.update(changes)
        return UniversalSettings(**d)

    def kernel_params(self) -> dict:
        """Plain dict for ``spiralbevel._core.universal_generator`` (the blank offset and vertical motion enter with
        a minus sign on the canonical left-hand machine, as in ``MachineSettings.kernel_params``)."""
        return dict(S=self.radial_setting, q=self.cradle_angle, g=self.machine_root_angle,
                    XD=self.machine_centre_to_back, XB=self.sliding_base, E=-self.blank_offset,
                    m=self.ratio_of_roll, roll=self.modified_roll, tilt=self.tilt, swivel=self.swivel,
                    radial=self.radial_motion, helical=self.helical_motion,
                    vertical=tuple(-c for c in self.vertical_motion))

    def to_dict(self, degrees: bool = True) -> dict:
        """Settings as a plain dict (the names of the fields); angles in degrees when ``degrees`` (I/O boundary),
        else rad."""
        d = asdict(self)
        for name in ("modified_roll", "helical_motion", "vertical_motion", "radial_motion"):
            d[name] = list(d[name])
        if degrees:
            for name in ("cradle_angle", "machine_root_angle", "tilt", "swivel"):
                d[name] = math.degrees(d[name])
        return d

    def summary_rows(self, cutter=None, member=None, side=None) -> list[tuple[str, str, str]]:
        """Rows (label, value, unit) for a shop-floor summary; angles in degrees. (``cutter``, ``member`` and
        ``side`` are accepted as ``MachineSettings.summary_rows`` takes them, and not used.)"""
        rows = [("Process", "generated" if self.generated else "Formate (non-generated)", "")]
        for key, label, unit, ang in _LABELS:
            v = getattr(self, key)
            rows.append((label, f"{math.degrees(v):.4f}" if ang else f"{v:.4f}", "deg" if ang else unit))
        for n, c in zip(("2C", "6D", "24E", "120F"), self.modified_roll):
            rows.append((f"Modified roll {n}", f"{c:.6g}", "-"))
        for name, key in (("Helical motion", "helical_motion"), ("Vertical motion", "vertical_motion"),
                          ("Radial motion", "radial_motion")):
            for k, c in enumerate(getattr(self, key), start=1):
                rows.append((f"{name} coefficient of psi_c^{k}", f"{c:.6g}", "mm"))
        return rows


@dataclass(frozen=True)
class UniversalPoints:
    """Generated (or Formate) flank points in the member frame.

    Attributes
    ----------
    points : (..., 3) float, mm
    normals : (..., 3) float
        Outward unit normals (out of the tooth material).
    u : (...) float, mm
        Blade parameter.
    theta : (...) float, rad
        Cutter angle from the (tilted) ray machine centre -> cutter centre.
    psi_c : (...) float, rad
        Cradle angle (0 on a Formate flank).
    discriminant : (...) float
        -R/sqrt(P^2 + Q^2) of the equation of meshing (|.| <= 1 where the cutter generates; 0 on Formate).
    """

    points: np.ndarray
    normals: np.ndarray
    u: np.ndarray
    theta: np.ndarray
    psi_c: np.ndarray
    discriminant: np.ndarray


class UniversalGenerator:
    """One cutter blade on the universal generator for one hand.

    Parameters
    ----------
    cutter : HeadCutter
        Any surface of revolution with ``points(u, theta)``, ``normals(u, theta)``, ``sign`` and ``nominal_radius``.
    settings : UniversalSettings
    hand : Hand
        Hand of the member cut (the right-hand machine mirrors the left-hand one, y -> -y).
    """

    def __init__(self, cutter, settings: UniversalSettings, hand):
        if not isinstance(settings, UniversalSettings):
            raise DesignError.single("settings", type(settings).__name__, "UniversalSettings", "-")
        self.cutter, self.settings, self.hand = cutter, settings, Hand(hand)
        self.up = settings.kernel_params()

    def _mirror(self, v):
        return v * _MIRROR if self.hand is Hand.RIGHT else v

    def _meridian(self, u):
        """Blade meridian (rho, z) and cutter normal components (n_r, n_z) at blade parameter u."""
        u = np.asarray(u, float)
        p = self.cutter.points(u, 0.0)
        n = self.cutter.normals(u, 0.0)
        return p[..., 0], p[..., 2], n[..., 0], n[..., 2]

    def machine_positions(self, psi_c=0.0) -> dict:
        """Machine-frame positions at cradle angle psi_c (canonical left-hand machine unless mirrored).

        Returns a dict: ``cutter_centre`` (3,) mm, ``cutter_axis`` (3,) unit, ``work_apex`` (3,) mm, ``work_axis``
        (3,) unit, ``work_rotation`` float rad.
        """
        psi = float(psi_c)
        centre, axis, _, apex, a = _u.positions(np.asarray(psi), self.up)
        return dict(cutter_centre=self._mirror(np.asarray(centre, float)),
                    cutter_axis=self._mirror(np.asarray(axis, float)),
                    work_apex=self._mirror(np.asarray(apex, float)), work_axis=self._mirror(a),
                    work_rotation=float(_u.work_rotation(psi, self.up)))

    def evaluate(self, u, psi_c, theta_ref=None) -> UniversalPoints:
        """Generated flank points at blade parameter ``u`` (mm) and cradle angle ``psi_c`` (rad), broadcast.

        The cutter angle solves the equation of meshing on the branch nearest ``theta_ref`` (rad; default: toward
        where the nominal cutter circle crosses the member's root line, displaced by the blank offset, far from the
        machine centre). Raises
        ``GeometryError`` where the cutter does not generate (no root), or on a Formate setting.
        """
        if not self.settings.generated:
            raise GeometryError.single("settings.generated", False, "true for evaluate (use formate)", "-")
        u, psi = np.broadcast_arrays(np.asarray(u, float), np.asarray(psi_c, float))
        rho, z, nr, nz = self._meridian(u)
        M, dM = _u.chain_and_rate(psi, self.up)
        ref = _u.reference_theta(psi, self.up, self.cutter.nominal_radius) if theta_ref is None else theta_ref
        theta, disc = _u.solve_theta(M, dM, rho, z, nr, nz, np.broadcast_to(ref, psi.shape))
        if np.any(~(np.abs(disc) <= 1.0)):
            raise GeometryError.single("settings", "-", "settings for which the cutter generates the flank", "-",
                                       "the equation of meshing has no solution: the cutter does not reach the blank")
        return self._points(M, rho, z, nr, nz, u, theta, psi, disc)

    def formate(self, u, theta) -> UniversalPoints:
        """Formate (non-generated) flank: the cutter surface at blade parameter ``u`` (mm) and cutter angle
        ``theta`` (rad) placed in the member frame with the cradle at psi_c = 0 (no roll, no motions)."""
        u, theta = np.broadcast_arrays(np.asarray(u, float), np.asarray(theta, float))
        rho, z, nr, nz = self._meridian(u)
        if getattr(self, "_M0", None) is None:          # the chain at psi_c = 0, the same for every point
            self._M0 = _u.chain(np.zeros(()), self.up).real
        M = np.broadcast_to(self._M0, u.shape + (4, 4))
        return self._points(M, rho, z, nr, nz, u, theta, np.zeros(u.shape), np.zeros(u.shape))

    def _points(self, M, rho, z, nr, nz, u, theta, psi, disc):
        p, n = _u.member_state(M, rho, z, nr, nz, theta)
        # cutter normal n_h points from the cutter into the cut for the outer blade (s = +1); outward = -s n_h
        nrm = -self.cutter.sign * n
        return UniversalPoints(points=self._mirror(p), normals=self._mirror(nrm), u=u, theta=theta, psi_c=psi,
                               discriminant=disc)

    def meshing_residual(self, u, theta, psi_c):
        """n . (dr/dpsi_c) / |dr/dpsi_c| in the member frame at (u, theta, psi_c), for a generated member."""
        u, theta, psi = np.broadcast_arrays(*(np.asarray(x, float) for x in (u, theta, psi_c)))
        rho, z, nr, nz = self._meridian(u)
        M, dM = _u.chain_and_rate(psi, self.up)
        r, _ = _u.cutter_point(rho, z, nr, nz, theta)
        v = np.einsum("...ij,...j->...i", dM[..., :3, :], r)
        return _u.meshing(M, dM, rho, z, nr, nz, theta) / np.linalg.norm(v, axis=-1)
