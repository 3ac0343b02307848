"""Loaded TCA of a real pair: the adapter from an unloaded :class:`~spiralbevel.meshing.tca_result.TCAResult` to the
LTCA driver (:func:`~spiralbevel.meshing.ltca.ltca.run_ltca`), and the FE tooth compliances from flank grids.

For every mesh position i and tooth pair k of the TCA (pinion tooth k against gear tooth k, docs/conventions.md
"Transmission error and the pair in contact (TCA)") the adapter builds a :class:`PairContact` in the fixed pair frame:

* contact point P = o1 + R_z(phi1 + 2 pi k/z1) r1 and common normal n = R_z(...) n1 (the pinion's outward normal,
  the direction of the force on the gear), from the TCA parameters and the contact problem's poses (misalignments
  included);
* the long axis e1 of the contact ellipse: the eigenvector of the smaller eigenvalue of the relative curvature
  K1 + K2 (Weingarten tensors of both surfaces in the pair frame), oriented away from the apex;
* exact separations w(s, t) along n on the tangent-plane grid around P (:func:`.separation.posed_separations`, both
  surfaces placed at the pair's own rotations phi1, phi2 of the TCA), so that w = 0 at P; the grid is sized from
  that contact's own Hertz ellipse (:func:`default_extents`), not from the largest ellipse of the cycle, so that
  its cells resolve the loaded contact width at every position;
* the pair's unloaded TE (seed 001 Eq. (1), sign of TCAResult);
* poses to the FE segment models: pinion r = R_z(phi1)^T (x - o1) on segment tooth k (the segment's tooth k is the
  reference tooth turned by +2 pi k/z1, as in TCA), gear r = (R(a2, phi2) B2)^T (x - o2) on segment tooth -k (TCA's
  gear tooth k is turned by -2 pi k/z2).

The LTCA driver then adds w_i = w_sep - te_k h_i with the lever arms h_i = ((q_i - o2) x n) . a2 (seed 001 Eq. (18),
docs/theory/ltca.md, Eqs. (L1)-(L4)). Potential contact points whose foot lies off a loaded flank grid are dropped, so
edge
contact of the TCA (extended surfaces) becomes contact along the flank edge. Pairs that the TCA leaves without
contact because another pair leads, although their real flanks touch along an edge a little behind it, get that
trailing edge contact (:mod:`.trailing`): under load they may carry load.
"""

from __future__ import annotations

import dataclasses
import logging
import warnings
from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from ..._core.rotations import rot_z
from ..._core.tca import relative_curvature, weingarten
from ...errors import DesignError, NoContactError, SpiralBevelWarning
from ..contact_problem import ContactProblem
from ..ellipse import hertz_semi_axes
from ..tca_result import ContactStatus
from .compliance import ToothCompliance, tooth_compliance
from .halfspace import STEEL, Material, contact_modulus
from .locate import locate_on_grid
from .ltca import APPROACH_TARGET, ContactPosition, PairContact, _check, run_ltca
from .ltca import torque_for_approach as _torque_for_approach
from .result import ARCSEC
from .trailing import TRAILING_WINDOW, follow_trailing_edges
from .mesher import mesh_tooth_segment
from .result import LTCAResult
from .separation import posed_separations

__all__ = ["LTCAModel", "ltca_model", "loaded_tca", "contact_positions", "segment_compliance", "default_extents",
           "FE_DEFAULTS"]

log = logging.getLogger(__name__)

#: default FE options of :func:`segment_compliance` (mesh_tooth_segment keywords and the element order)
FE_DEFAULTS = dict(n_teeth=3, thickness_divisions=2, space_divisions=2, rim_layers=2, rim_thickness=None, order=2)

SIDES = ("convex", "concave")


# ---------------------------------------------------------------------------------------------------- compliance
def _grid_points(g, name):
    arr = np.asarray(getattr(g, "points", getattr(g, "point", g)), float)
    if arr.ndim != 3 or arr.shape[-1] != 3 or min(arr.shape[:2]) < 2 or not np.all(np.isfinite(arr)):
        raise DesignError.single(name, f"shape {arr.shape}", "finite (n_face >= 2, n_profile >= 2, 3) grid", "mm",
                                 "flank grid (ToothFlank.grid points, member frame)")
    return arr


def segment_compliance(convex, concave, z: int, side: str, *, material: Material = STEEL, fe_options=None,
                       cache_dir=None) -> ToothCompliance:
    """FE flexibility of the ``side`` flanks of a tooth segment built from the two flank grids of one tooth.

    Parameters
    ----------
    convex, concave : (n_face, n_profile, 3) float, mm, or FlankPoints
        Flank grids of the reference tooth in the member frame used by the TCA (phasing rotation applied).
    z : int
        Number of teeth of the member.
    side : {"convex", "concave"}
        Loaded flank.
    material : Material
    fe_options : dict, optional
        Overrides of :data:`FE_DEFAULTS` (``n_teeth``, ``thickness_divisions``, ``space_divisions``,
        ``rim_layers``, ``rim_thickness`` mm, ``order``).
    cache_dir : path, optional
        Disk cache of the FE result (default ``$SPIRALBEVEL_CACHE`` or ``~/.cache/spiralbevel``).

    Returns
    -------
    ToothCompliance

    Raises
    ------
    MissingDependencyError
        scikit-fem is missing and the result is not cached.
    """
    opts: dict[str, Any] = dict(FE_DEFAULTS)
    for key, v in (fe_options or {}).items():
        if key not in opts:
            raise DesignError.single(f"fe_options[{key!r}]", v, f"one of {sorted(opts)}", "-", "FE tooth compliance")
        opts[key] = v
    order = opts.pop("order")
    mesh = mesh_tooth_segment(_grid_points(convex, "convex"), _grid_points(concave, "concave"), z, **opts)
    return tooth_compliance(mesh, side, material, order=order, cache_dir=cache_dir)


# ---------------------------------------------------------------------------------------------------- positions
def _contains(surface, params, tol=1e-9):
    """The surface's ``contains`` (True where it has none); NaN parameters are outside. With ``boundary_margins``, a
    point within ``tol`` (the margins' units, mm or rad) of an edge is on the flank: the foot of the grid point at an
    edge contact lies on the edge up to the rounding of the contact solve (about 1e-13)."""
    from ..contact_surface import surface_contains

    params = np.asarray(params, float)
    fin = np.all(np.isfinite(params), axis=-1)
    p = np.where(fin[..., None], params, 0.0)
    if hasattr(surface, "boundary_margins"):
        with np.errstate(invalid="ignore"):
            g = np.asarray(surface.boundary_margins(p), float)
        return fin & np.all(g >= -tol, axis=-1)
    return fin & surface_contains(surface, p)


def _on_edge(surface, params, tol=1e-8):
    """True where ``params (m, 2)`` lie on a boundary of the surface's real flank (a margin within ``tol``)."""
    if not hasattr(surface, "boundary_margins"):
        return np.zeros(len(params), bool)
    with np.errstate(invalid="ignore"):
        g = np.asarray(surface.boundary_margins(params), float)
    return np.any(np.abs(g) < tol, axis=-1)


def _pair_states(pinion, gear, kinematics, tca, misalignment):
    """Pair-frame contact data of every valid (position, pair) of the TCA."""
    prob = ContactProblem(pinion, gear, kinematics, misalignment)
    if (prob.z1, prob.z2) != (int(tca.z1), int(tca.z2)):
        raise DesignError.single("kinematics", (prob.z1, prob.z2), f"the TCA's (z1, z2) = ({tca.z1}, {tca.z2})", "-",
                                 "loaded TCA")
    k = np.asarray(tca.pairs, int)
    # every contact of the real flanks is loaded, surface (OK, LINE) or edge (EDGE: a boundary curve of one flank
    # against the other flank; its separations are those of the touched flank and the edge member's flank, whose
    # cells beyond the edge are dropped in contact_positions)
    status = np.asarray(tca.status_pairs)
    valid = (status != ContactStatus.NO_CONTACT) & np.isfinite(tca.te_pairs)
    ii, jj = np.nonzero(valid)
    phi1 = tca.phi1[ii]
    phi2 = tca.phi2_pairs[ii, jj]
    p1e = phi1 + 2 * np.pi * k[jj] / prob.z1
    p2e = phi2 - 2 * np.pi * k[jj] / prob.z2
    x = np.concatenate([tca.params1[ii, jj], tca.params2[ii, jj], p2e[:, None]], -1)
    r1, n1, dr1, dn1, r2, n2, dr2, dn2 = prob.state(x)
    R1, R2, o1, o2 = prob.pose(p1e, p2e)
    mv = lambda R, v: np.einsum("mij,mj->mi", R, v)  # noqa: E731
    P, n = o1 + mv(R1, r1), mv(R1, n1)
    P2 = o2 + mv(R2, r2)
    # at an edge of the pinion the contact normal is the touched gear flank's (outward from the pinion: -n2)
    pin_edge = _on_edge(prob.pinion, x[:, 0:2]) & (status[ii, jj] == ContactStatus.EDGE)
    n = np.where(pin_edge[:, None], -mv(R2, n2), n)
    gap = max(np.max(np.abs(P - tca.point_fixed[ii, jj]), initial=0.0), np.max(np.abs(P2 - P), initial=0.0))
    if gap > 1e-6 * (1.0 + np.max(np.abs(P), initial=0.0)):
        raise DesignError.single("misalignment / surfaces", f"contact points {gap:.3e} mm apart",
                                 "the surfaces and misalignment of the TCA", "mm", "loaded TCA adapter")
    W1 = R1 @ weingarten(dr1, dn1) @ np.swapaxes(R1, -1, -2)
    W2 = R2 @ weingarten(dr2, dn2) @ np.swapaxes(R2, -1, -2)
    lam, dirs = relative_curvature(W1, W2, n)
    e1 = dirs[:, 0] * np.where(np.einsum("mi,mi->m", dirs[:, 0], P) < 0, -1.0, 1.0)[:, None]
    return dict(prob=prob, ii=ii, jj=jj, k=k[jj], phi1=phi1, phi2=phi2, P=P, n=n, e1=e1, lam=lam, R1=R1, R2=R2,
                o1=np.broadcast_to(o1, P.shape), o2=np.broadcast_to(o2, P.shape), valid=valid)


def _cells(n, half):
    d = 2 * half / n
    return -half + d * (np.arange(n) + 0.5)


class _Tabulated:
    """Separations tabulated on the driver's grid (callable ``(s, t) -> (ns, nt)`` as PairContact expects)."""

    def __init__(self, s, t, w):
        self.s, self.t, self.w = s, t, w

    def __call__(self, s, t):
        if np.shape(s) != self.s.shape or np.shape(t) != self.t.shape or not (
                np.allclose(s, self.s, rtol=0, atol=1e-12) and np.allclose(t, self.t, rtol=0, atol=1e-12)):
            raise DesignError.single("grid", (len(np.atleast_1d(s)), len(np.atleast_1d(t))),
                                     "the grid and extents the positions were built with", "-", "LTCA separations")
        return self.w


#: elastic approach (mm) at which the potential-contact grid is sized: 4 x the approach target covers the loaded
#: contact up to about 8 x the approach torque (approach ~ load^(2/3) in Hertz contact)
SIZING_APPROACH = 4.0 * APPROACH_TARGET
#: grid half extents = this margin x the Hertz semi-axes at SIZING_APPROACH
SIZING_MARGIN = 1.25
#: cap (mm) of a half extent (line and near-line contact: the flank ends bound the contact, points off it are dropped)
SIZING_CAP = 20.0


def default_extents(lam, approach=SIZING_APPROACH, margin=SIZING_MARGIN, cap=SIZING_CAP):
    """Half extents (..., 2) mm of the potential-contact grid of contacts with relative curvatures ``lam (..., 2)``:
    ``margin`` x the Hertz semi-axes at the elastic approach ``approach``
    (:func:`~spiralbevel.meshing.ellipse.hertz_semi_axes`), each capped at ``cap``.

    Sized per position and pair from that contact alone, the default ``grid`` (21, 7) puts about 2 x 7 / (2 x 1.25 x
    2) ~ 3 cells across the loaded width at the approach torque, and more at the higher torques of a rating."""
    lam = np.asarray(lam, float)
    ab = margin * hertz_semi_axes(lam, approach)
    # line contact across (lam_2 <= 0 cannot carry load in the tangent plane): a 1 mm wide strip
    ab[..., 1] = np.where(np.isfinite(ab[..., 1]), ab[..., 1], 1.0)
    return np.minimum(ab, cap)


def contact_positions(pinion, gear, kinematics, tca, *, misalignment=None, grid=(21, 7), half_length=None,
                      half_width=None, trailing_window=None):
    """Unloaded contact of every TCA position and pair as LTCA input (see the module docstring).

    Parameters
    ----------
    pinion, gear : ContactSurface
        The surfaces the TCA was run on (member frames).
    kinematics : object
        ``z1``, ``z2``, ``shaft_angle`` (as for :func:`~spiralbevel.meshing.tca.solve_tca`).
    tca : TCAResult
    misalignment : Misalignment, optional
        The one of the TCA (checked: the reconstructed contact points must meet).
    grid : (int, int)
        Potential contact points per pair along the ellipse's major and minor axes (odd counts put a point on the
        contact point itself).
    half_length, half_width : float, mm, optional
        Half extents of that grid at every position and pair; default: each contact's own Hertz ellipse
        (:func:`default_extents`, stored in ``PairContact.extents``).
    trailing_window : float, rad, optional
        Edge contacts that the TCA does not follow because another pair leads (a pair whose surface contact ran off
        its flank) are added where they trail the leading contact by at most this TE difference
        (:func:`~spiralbevel.meshing.ltca.trailing.follow_trailing_edges`; default 1 % of the gear's angular pitch).

    Returns
    -------
    positions : list of ContactPosition
        ``pinion_angle`` = phi1 - phi10; pairs in ``tca.pairs`` order, None where the TCA found no contact.
    extents : (float or None, float or None), mm
        The half extents given (None: per contact).

    Raises
    ------
    NoContactError
        A position where the TCA found no contact for any pair.
    """
    _check(1.0, [None], grid, half_length, half_width)
    tca, _ = follow_trailing_edges(ContactProblem(pinion, gear, kinematics, misalignment), tca, trailing_window)
    st = _pair_states(pinion, gear, kinematics, tca, misalignment)
    none = np.flatnonzero(~st["valid"].any(axis=1))
    if none.size:
        i = int(none[0])
        raise NoContactError(f"no tooth pair in contact in the TCA at mesh position {i} (phi1 = {tca.phi1[i]:.6g} "
                             f"rad): loaded TCA needs contact at every position")
    prob = st["prob"]
    m = len(st["ii"])
    # per pair and position: the half extents of its own contact (Hertz ellipse), unless given
    ext = default_extents(st["lam"])
    if half_length is not None:
        ext[:, 0] = float(half_length)
    if half_width is not None:
        ext[:, 1] = float(half_width)
    R1f = rot_z(st["phi1"])                                      # pinion member -> fixed (actual rotation)
    R2f = np.einsum("mij,mjk->mik", st["R2"], rot_z(2 * np.pi * st["k"] / prob.z2))  # R(a2, phi2) B2
    # one batched separation solve, each contact on its own grid
    s = np.stack([_cells(grid[0], hl) for hl in ext[:, 0]]) if m else np.zeros((0, grid[0]))
    t = np.stack([_cells(grid[1], hw) for hw in ext[:, 1]]) if m else np.zeros((0, grid[1]))
    sep = posed_separations(prob.pinion, prob.gear, (st["R1"], st["o1"]), (st["R2"], st["o2"]),
                            tca.params1[st["ii"], st["jj"]], tca.params2[st["ii"], st["jj"]], st["P"], st["n"],
                            st["e1"], s, t)
    # potential contact points whose foot lies off either real flank carry no load (beyond a top edge, the toe, the
    # heel or the fillet junction there is no tooth surface): NaN separations are dropped by the driver
    on = _contains(prob.pinion, sep.params1) & _contains(prob.gear, sep.params2)
    w = [_Tabulated(s[a], t[a], np.where(on[a], sep.w[a], np.nan)) for a in range(m)]
    n_pos, n_pairs = tca.te_pairs.shape
    table = [[None] * n_pairs for _ in range(n_pos)]
    for a in range(m):
        i, j = int(st["ii"][a]), int(st["jj"][a])
        table[i][j] = PairContact(
            point=st["P"][a], normal=st["n"][a], direction=st["e1"][a], te=float(tca.te_pairs[i, j]),
            separation=w[a], to_pinion=(R1f[a].T, st["o1"][a]), to_gear=(R2f[a].T, st["o2"][a]),
            tooth_pinion=int(st["k"][a]), tooth_gear=-int(st["k"][a]), extents=(float(ext[a, 0]), float(ext[a, 1])),
            edge=bool(tca.status_pairs[i, j] == ContactStatus.EDGE))
    positions = [ContactPosition(float(tca.phi1[i] - tca.phi1_mean), table[i]) for i in range(n_pos)]
    return positions, (half_length, half_width)


# ---------------------------------------------------------------------------------------------------- model
@dataclass(frozen=True)
class LTCAModel:
    """Everything loaded TCA needs except the torque: unloaded contacts and FE compliances (reusable for sweeps).

    Attributes
    ----------
    positions : list of ContactPosition
    pinion_compliance, gear_compliance : ToothCompliance or None
        None: rigid teeth (contact flattening only).
    gear_axis, gear_origin : (3,) float
        a2 and o2 of the (misaligned) assembly, pair frame.
    grid : (int, int)
    half_length, half_width : float or None, mm
        Common half extents of the potential-contact grids, None where each contact carries its own.
    z1, z2 : int
    pairs : tuple of int
        Tooth-pair indices k of the TCA (pinion tooth k, gear tooth k), in the order of each position's pairs.
    material_pinion, material_gear : Material
    trailing_window : float or None, rad
        TE lag up to which trailing edge contacts were followed (:func:`.trailing.follow_trailing_edges`);
        :meth:`run` warns when the loaded pair lags its unloaded position by more (pairs beyond may then touch).
    """

    positions: list
    pinion_compliance: Optional[ToothCompliance]
    gear_compliance: Optional[ToothCompliance]
    gear_axis: np.ndarray
    gear_origin: np.ndarray
    grid: tuple
    half_length: Optional[float]
    half_width: Optional[float]
    z1: int
    z2: int
    pairs: tuple
    material_pinion: Material = STEEL
    material_gear: Material = STEEL
    trailing_window: Optional[float] = None

    def _kw(self):
        return dict(gear_axis=self.gear_axis, gear_origin=self.gear_origin, grid=self.grid,
                    half_length=self.half_length, half_width=self.half_width, material_pinion=self.material_pinion,
                    material_gear=self.material_gear)

    def run(self, torque: float, *, approach_target: float | None = APPROACH_TARGET) -> LTCAResult:
        """Loaded TCA at gear torque ``torque`` (N mm, > 0); ``points1``/``points2`` of the result are on the
        reference teeth (flank coordinates, as in TCAResult)."""
        res = run_ltca(self.positions, torque, self.pinion_compliance, self.gear_compliance,
                       approach_target=approach_target, **self._kw())
        ks = np.asarray(self.pairs, int)
        p1, p2 = [], []
        for x1, x2, pr in zip(res.points1, res.points2, res.pair_of_point):
            k = ks[pr]
            # pair k sits on pinion tooth k (2 pi k / z1 ahead of the reference tooth) and on gear tooth -k
            # (PairContact.tooth_gear): turn each back by its own tooth's angle
            p1.append(np.einsum("mij,mj->mi", rot_z(-2 * np.pi * k / self.z1), x1))
            p2.append(np.einsum("mij,mj->mi", rot_z(2 * np.pi * k / self.z2), x2))
        names = tuple(f"pair {int(k):+d}" for k in ks)
        if self.trailing_window is not None:
            lag = np.nanmax(np.asarray(res.te_unloaded) - np.asarray(res.te_loaded), initial=0.0) * ARCSEC
            if lag > self.trailing_window:
                warnings.warn(f"loaded TCA: the loaded pair lags its unloaded position by {lag / ARCSEC:.1f} arcsec, "
                              f"more than the {self.trailing_window / ARCSEC:.1f} arcsec up to which trailing edge "
                              "contacts were followed; pairs beyond may touch", SpiralBevelWarning, stacklevel=2)
        return dataclasses.replace(res, points1=p1, points2=p2, pair_names=names)

    def approach_torque(self, target: float = APPROACH_TARGET, position: int | None = None) -> float:
        """Gear torque (N mm) at which the tooth approach at the mean contact point is ``target`` mm (seed 001
        §4.3.2: 0.00635 mm, Gleason's 0.00025 in); ``position`` defaults to the one nearest phi1 = phi10."""
        angles = np.array([p.pinion_angle for p in self.positions])
        m = int(np.argmin(np.abs(angles))) if position is None else int(position)
        return _torque_for_approach(self.positions[m], target, self.pinion_compliance, self.gear_compliance,
                                    np.asarray(self.gear_axis, float), np.asarray(self.gear_origin, float), self.grid,
                                    self.half_length, self.half_width,
                                    contact_modulus(self.material_pinion, self.material_gear), m)


def _check_on_flank(P_member, grid, name, tol):
    """The contact point must lie on (or within ``tol`` of) the loaded flank grid: catches phasing/side mix-ups."""
    i, j, xi, eta, inside = locate_on_grid(grid, P_member[None])
    foot = ((1 - xi) * (1 - eta) * grid[i, j] + xi * (1 - eta) * grid[i + 1, j] + (1 - xi) * eta * grid[i, j + 1]
            + xi * eta * grid[i + 1, j + 1])
    d = float(np.linalg.norm(foot[0] - P_member))
    if d > tol:
        raise DesignError.single(name, f"{d:.3f} mm from the TCA mean contact point", f"<= {tol} mm", "mm",
                                 "the loaded flank grid must be the TCA surface in the same member frame "
                                 "(phasing rotation applied, loaded side as in `sides`)")


def ltca_model(pinion_surface, gear_surface, kinematics, tca_result, *, pinion_grids=None, gear_grids=None,
               z1: int | None = None, z2: int | None = None, sides=("concave", "convex"), misalignment=None,
               material: Material = STEEL, fe_options=None, cache_dir=None, grid=(21, 7), half_length=None,
               half_width=None, rigid: bool = False, grid_tol: float = 0.1) -> LTCAModel:
    """Build the loaded-TCA model of a pair from its unloaded TCA (see :func:`loaded_tca` for the parameters).

    ``rigid=True`` skips the FE compliances (contact flattening only; no grids needed).
    """
    z1 = int(tca_result.z1) if z1 is None else int(z1)
    z2 = int(tca_result.z2) if z2 is None else int(z2)
    if (z1, z2) != (int(tca_result.z1), int(tca_result.z2)):
        raise DesignError.single("z1, z2", (z1, z2), f"({tca_result.z1}, {tca_result.z2}) of the TCA", "-",
                                 "loaded TCA")
    if len(sides) != 2 or any(s not in SIDES for s in sides):
        raise DesignError.single("sides", sides, "(pinion side, gear side), each 'convex' or 'concave'", "-",
                                 "loaded flanks")
    window = TRAILING_WINDOW * 2 * np.pi / z2
    positions, (hl, hw) = contact_positions(pinion_surface, gear_surface, kinematics, tca_result,
                                            misalignment=misalignment, grid=grid, half_length=half_length,
                                            half_width=half_width, trailing_window=window)
    prob = ContactProblem(pinion_surface, gear_surface, kinematics, misalignment)
    a1, o1, a2, o2, _ = prob.axes
    comps: list[Any] = [None, None]
    if not rigid:
        j0 = int(np.argmin(np.abs(np.asarray(tca_result.pairs))))
        m0 = len(tca_result.phi1) // 2
        for idx, (grids, z, side, name, pt) in enumerate((
                (pinion_grids, z1, sides[0], "pinion_grids", tca_result.point1[m0, j0]),
                (gear_grids, z2, sides[1], "gear_grids", tca_result.point2[m0, j0]))):
            if grids is None or len(grids) != 2:
                raise DesignError.single(name, None if grids is None else len(grids), "(convex, concave) grids",
                                         "mm", "FE tooth compliance (or rigid=True)")
            cv, cc = (_grid_points(g, f"{name}[{q}]") for q, g in enumerate(grids))
            if np.all(np.isfinite(pt)):
                _check_on_flank(np.asarray(pt, float), cv if side == "convex" else cc, f"{name} ({side})", grid_tol)
            comps[idx] = segment_compliance(cv, cc, z, side, material=material, fe_options=fe_options,
                                            cache_dir=cache_dir)
    return LTCAModel(positions, comps[0], comps[1], np.asarray(a2, float), np.asarray(o2, float), tuple(grid),
                     hl, hw, z1, z2,
                     tuple(int(k) for k in tca_result.pairs), material, material, window)


def loaded_tca(pinion_surface, gear_surface, kinematics, tca_result, torque: float, *, pinion_grids=None,
               gear_grids=None, z1: int | None = None, z2: int | None = None, sides=("concave", "convex"),
               misalignment=None, material: Material = STEEL, fe_options=None, cache_dir=None, grid=(21, 7),
               half_length=None, half_width=None, rigid: bool = False,
               approach_target: float | None = APPROACH_TARGET) -> LTCAResult:
    """Loaded tooth contact analysis of a pair over the mesh cycle of its unloaded TCA (seed 001 §4.3.2, Eq. (18)).

    Parameters
    ----------
    pinion_surface, gear_surface : ContactSurface
        The flanks the TCA was run on (member frames, e.g. ``phased_for_pair`` of face-milled flanks).
    kinematics : object
        ``z1``, ``z2``, ``shaft_angle`` (rad).
    tca_result : TCAResult
        From :func:`~spiralbevel.meshing.tca.solve_tca` with these surfaces (3 pairs (-1, 0, 1) for a 3-tooth FE
        segment).
    torque : float, N mm
        Gear torque (> 0).
    pinion_grids, gear_grids : ((n_face, n_profile, 3), (n_face, n_profile, 3)) float, mm
        (convex, concave) flank grids of one tooth of each member in the member frame of the TCA surfaces (the
        phasing rotation applied; ``ToothFlank.grid(...).points`` or FlankPoints). They bound the FE tooth model.
    z1, z2 : int, optional
        Tooth numbers (checked against the TCA).
    sides : (str, str)
        Loaded (pinion, gear) flanks; drive side ("concave", "convex").
    misalignment : Misalignment, optional
        The misalignment of the TCA.
    material : Material
        Both members (default steel).
    fe_options : dict, optional
        See :func:`segment_compliance` (coarse meshes are fast, fine meshes converge).
    cache_dir : path, optional
        FE cache directory.
    grid : (int, int)
        Potential contact points per pair (major, minor axis).
    half_length, half_width : float, mm, optional
        Grid half extents (default: per position and pair, 1.25 x the Hertz ellipse of that contact at an approach of
        4 x 0.00635 mm, :func:`default_extents`).
    rigid : bool
        Skip the FE compliances (contact flattening only).
    approach_target : float or None, mm
        Also find the torque of this approach at the mean contact point (``result.approach_torque``).

    Returns
    -------
    LTCAResult
        ``points1``/``points2`` on the reference teeth (member frames).

    Raises
    ------
    DesignError
        Bad torque, grids, sides or tooth numbers; surfaces/misalignment not those of the TCA.
    NoContactError
        A TCA position without contact.
    MissingDependencyError
        scikit-fem missing for an uncached FE compliance (extra ``fem``).
    """
    if not (isinstance(torque, (int, float, np.floating, np.integer)) and np.isfinite(torque) and torque > 0):
        raise DesignError.single("torque", torque, "> 0", "N mm", "loaded TCA gear torque")
    model = ltca_model(pinion_surface, gear_surface, kinematics, tca_result, pinion_grids=pinion_grids,
                       gear_grids=gear_grids, z1=z1, z2=z2, sides=sides, misalignment=misalignment,
                       material=material, fe_options=fe_options, cache_dir=cache_dir, grid=grid,
                       half_length=half_length, half_width=half_width, rigid=rigid)
    return model.run(torque, approach_target=approach_target)
