"""Tooth root stress from the FE tooth model under the loaded contact forces of an LTCA: :func:`fe_root_stress`.

For each member a three-tooth segment with its generated root fillets (flank grids with fillet rows,
:meth:`~spiralbevel.generation.flank.ToothFlank.grid` ``n_fillet``) is meshed with
:func:`~spiralbevel.meshing.ltca.mesher.mesh_tooth_segment`, clamped at the rim, and factorised once
(:func:`~spiralbevel.rating.fe_solid.solid_model`). The contact forces of the LTCA (normal forces at the potential
contact points, no friction) are distributed to the four vertices of the flank-grid cell that holds each point with
the bilinear weights of the LTCA compliance, pointing into the tooth.

The load cases follow the middle tooth (tooth 0) through its whole engagement: at every mesh position and for every
tooth pair j that carries load there, tooth 0 takes the role of pair j and the other pairs' forces go on the
neighbouring teeth at their pitch offsets (teeth outside the segment are left out). The maximum principal stress is
read at the vertices of the fillet rows of both flanks of tooth 0 (nodal-averaged, :mod:`.fe_solid`); the largest over
all load cases is reported with its position (face-width station, height above the root line, axial-section
coordinates) and compared with sigma_F0 and sigma_F of Method B1 at the LTCA's torque (docs/rating.md, "FE tooth root
stress").
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any
from dataclasses import dataclass

import numpy as np

from ..errors import DesignError
from .fe_loads import contact_load_cases
from .fe_solid import max_principal, solid_model

__all__ = ["MemberRootStress", "member_root_stress", "fe_root_stress", "compare_root_stress", "contact_load_cases"]

#: FE options of the stress model (mesh_tooth_segment keywords): finer across the tooth than the LTCA compliance
STRESS_FE_DEFAULTS = dict(n_teeth=3, thickness_divisions=4, space_divisions=2, rim_layers=2, rim_thickness=None)


@dataclass(frozen=True)
class MemberRootStress:
    """Maximum principal stress along the root fillet of the middle tooth of one member's FE segment.

    Attributes
    ----------
    member : str
        ``"pinion"`` or ``"gear"``.
    loaded_side : str
        Flank carrying the contact (``"convex"`` or ``"concave"``).
    sigma1 : dict
        ``side -> (n_face, n_rows)`` float, N/mm^2: envelope (largest over the load cases) of the maximum principal
        stress on each flank grid of tooth 0, fillet rows first.
    n_fillet : int
        Fillet rows of each flank grid (row 0 the root line, row n_fillet - 1 the fillet/blade junction).
    grids : dict
        ``side -> (n_face, n_rows, 3)`` float, mm: the flank grids of tooth 0 (member frame).
    sigma1_max : float, N/mm^2
        Largest maximum principal stress on the fillet rows over all load cases.
    side_max : str
        Flank of that maximum.
    index_max : (int, int)
        Grid index (face station i, row j) of the maximum.
    face_fraction : float, -
        Arc length along the root line from the toe to the station of the maximum over the root line's length.
    height_above_root : float, mm
        Arc length along the fillet row from the root line to the maximum.
    radius, axial : float, mm
        Axial-section coordinates of the maximum (distance from the member axis, position along it).
    case_max : (int, int)
        (mesh position, pair index) of the load case of the maximum.
    pinion_angle_max : float, rad
        Pinion rotation of that mesh position.
    load_cases : int
    applied_force : (n_cases, 3) float, N
        Sum of the applied contact forces of every load case (member frame).
    reaction_force : (n_cases, 3) float, N
        Sum of the clamp reactions of every load case (= -applied_force in equilibrium).
    n_elements, n_dofs : int
    """

    member: str
    loaded_side: str
    sigma1: dict
    n_fillet: int
    grids: dict
    sigma1_max: float
    side_max: str
    index_max: tuple
    face_fraction: float
    height_above_root: float
    radius: float
    axial: float
    case_max: tuple
    pinion_angle_max: float
    load_cases: int
    applied_force: np.ndarray
    reaction_force: np.ndarray
    n_elements: int
    n_dofs: int

    def summary(self) -> dict:
        """JSON-ready figures (stress N/mm^2, lengths mm, angle deg)."""
        return {"sigma1_max": self.sigma1_max, "flank": self.side_max, "loaded_flank": self.loaded_side,
                "face_fraction_from_toe": self.face_fraction, "height_above_root_mm": self.height_above_root,
                "axial_section_radius_mm": self.radius, "axial_section_z_mm": self.axial,
                "mesh_position": int(self.case_max[0]), "pair": int(self.case_max[1]),
                "pinion_angle_deg": math.degrees(self.pinion_angle_max), "load_cases": self.load_cases,
                "max_equilibrium_error_N": float(np.max(np.abs(self.applied_force + self.reaction_force))),
                "elements": self.n_elements, "dofs": self.n_dofs}


def _arc(points):
    seg = np.linalg.norm(np.diff(points, axis=0), axis=-1)
    return np.concatenate([[0.0], np.cumsum(seg)])


def member_root_stress(member, convex, concave, z, side, n_fillet, points, pair_of_point, force, teeth_of_pairs,
                       pinion_angles, *, youngs_modulus=206000.0, poisson_ratio=0.3, fe_options=None, order=2,
                       tol=0.5) -> MemberRootStress:
    """Maximum principal stress along the root fillet of one member under the LTCA contact forces.

    Parameters
    ----------
    member : str
        ``"pinion"`` or ``"gear"`` (label).
    convex, concave : (n_face, n_fillet + n_profile, 3) float, mm
        Flank grids of the reference tooth with their fillet rows (member frame of the LTCA points).
    z : int
        Number of teeth.
    side : str
        Loaded flank.
    n_fillet : int
        Fillet rows of the grids (>= 2).
    points, pair_of_point, force : lists per mesh position
        LTCA contact points on the reference tooth (``points1``/``points2``), their pairs and normal forces (N).
    teeth_of_pairs : (n_pairs,) int
        Segment tooth of each pair.
    pinion_angles : (n_pos,) float, rad
    youngs_modulus, poisson_ratio : float
        N/mm^2, -.
    fe_options : dict, optional
        Overrides of ``STRESS_FE_DEFAULTS``.
    order : {1, 2}
    tol : float, mm
        See :func:`contact_load_cases`.

    Returns
    -------
    MemberRootStress
    """
    from ..meshing.ltca.mesher import mesh_tooth_segment

    if not (isinstance(n_fillet, (int, np.integer)) and n_fillet >= 2):
        raise DesignError.single("n_fillet", n_fillet, "integer >= 2", "-", "FE root stress (fillet rows)")
    opts = dict(STRESS_FE_DEFAULTS)
    for key, v in (fe_options or {}).items():
        if key not in opts:
            raise DesignError.single(f"fe_options[{key!r}]", v, f"one of {sorted(opts)}", "-", "FE root stress")
        opts[key] = v
    mesh = mesh_tooth_segment(np.asarray(convex, float), np.asarray(concave, float), z, **opts)
    if 0 not in mesh.teeth:
        raise DesignError.single("n_teeth", opts["n_teeth"], ">= 1", "-", "FE root stress")
    F, cases = contact_load_cases(mesh, side, points, pair_of_point, force, teeth_of_pairs, tol)
    model = solid_model(mesh, youngs_modulus, poisson_ratio, order)
    U = model.solve(F)
    S = model.vertex_stress(U)
    s1 = max_principal(S)  # (n_cases, nv)
    env, grids = {}, {}
    best: tuple[float, Any, Any, Any] = (-np.inf, None, None, None)
    for sd in ("convex", "concave"):
        nodes = mesh.flank_nodes[(0, sd)]
        grids[sd] = mesh.vertices[nodes]
        vals = s1[:, nodes]  # (n_cases, n_face, n_rows)
        env[sd] = vals.max(axis=0)
        fil = vals[:, :, :n_fillet]
        c, i, j = np.unravel_index(int(np.argmax(fil)), fil.shape)
        if fil[c, i, j] > best[0]:
            best = (float(fil[c, i, j]), sd, (int(i), int(j)), int(c))
    val, sd, (i, j), c = best
    g = grids[sd]
    root_arc = _arc(g[:, 0])
    P = g[i, j]
    m, pair = cases[c]
    return MemberRootStress(
        member=member, loaded_side=side, sigma1=env, n_fillet=int(n_fillet), grids=grids, sigma1_max=val, side_max=sd,
        index_max=(i, j), face_fraction=float(root_arc[i] / root_arc[-1]),
        height_above_root=float(_arc(g[i, : j + 1])[-1]),
        radius=float(np.hypot(P[0], P[1])), axial=float(P[2]), case_max=(m, pair),
        pinion_angle_max=float(np.asarray(pinion_angles)[m]), load_cases=len(cases),
        applied_force=F.sum(axis=1), reaction_force=model.reactions(U), n_elements=len(mesh.tets),
        n_dofs=int(model.basis.N))


def fe_root_stress(ltca, pinion_grids, gear_grids, z1: int, z2: int, *, pairs, sides=("concave", "convex"),
                   n_fillet: int, youngs_modulus: float = 206000.0, poisson_ratio: float = 0.3, fe_options=None,
                   order: int = 2, tol: float = 0.5) -> dict:
    """Root stress of pinion and gear under the contact forces of an LTCA.

    Parameters
    ----------
    ltca : LTCAResult
        From :meth:`~spiralbevel.meshing.ltca.from_tca.LTCAModel.run` (``points1``/``points2`` on the reference teeth).
    pinion_grids, gear_grids : ((n_face, n_rows, 3), (n_face, n_rows, 3)) float, mm
        (convex, concave) flank grids with ``n_fillet`` fillet rows first, in the member frames of the LTCA (phasing
        rotation applied).
    z1, z2 : int
    pairs : sequence of int
        Tooth-pair indices k of the LTCA's pairs (pinion tooth k, gear tooth -k of the segments).
    sides : (str, str)
        Loaded (pinion, gear) flanks.
    n_fillet : int
    youngs_modulus, poisson_ratio : float
        N/mm^2, -.
    fe_options : dict, optional
        Overrides of ``STRESS_FE_DEFAULTS``.
    order : {1, 2}
    tol : float, mm
        See :func:`contact_load_cases`.

    Returns
    -------
    dict
        ``{"pinion": MemberRootStress, "gear": MemberRootStress}``.
    """
    ks = np.asarray(pairs, int)
    out = {}
    for member, grids, z, side, pts, teeth in (("pinion", pinion_grids, z1, sides[0], ltca.points1, ks),
                                               ("gear", gear_grids, z2, sides[1], ltca.points2, -ks)):
        out[member] = member_root_stress(member, grids[0], grids[1], z, side, n_fillet, pts, ltca.pair_of_point,
                                         ltca.force, teeth, ltca.pinion_angles, youngs_modulus=youngs_modulus,
                                         poisson_ratio=poisson_ratio, fe_options=fe_options, order=order, tol=tol)
    return out


def compare_root_stress(blank, inp, ltca, stresses: dict) -> dict:
    """FE root stresses against sigma_F0 and sigma_F of Method B1 re-rated at the LTCA's torque.

    Parameters
    ----------
    blank : BevelBlank
    inp : RatingInput
        Its torque is replaced by the LTCA's (T1 = T2 / u).
    ltca : LTCAResult
        Read: ``torque`` (gear, N mm).
    stresses : dict
        From :func:`fe_root_stress`.

    Returns
    -------
    dict
        ``T1_ltca`` (N m); per member (``pinion`` suffix 1, ``gear`` suffix 2): ``sigma_F0``, ``sigma_F`` (N/mm^2),
        the FE figures of :meth:`MemberRootStress.summary` and the ratios ``sigma1/sigma_F0``, ``sigma1/sigma_F``.
    """
    from .rate import rate_iso10300

    u = blank.z2 / blank.z1
    T1 = float(ltca.torque) / (1000.0 * u)
    res = rate_iso10300(blank, dataclasses.replace(inp, T1=T1))
    out = {"T1_ltca": T1}
    for member, sfx in (("pinion", "1"), ("gear", "2")):
        st = stresses[member]
        f0, f = res[f"sigma_F0{sfx}"], res[f"sigma_F{sfx}"]
        out[member] = {**st.summary(), "sigma_F0": f0, "sigma_F": f, "sigma1/sigma_F0": st.sigma1_max / f0,
                       "sigma1/sigma_F": st.sigma1_max / f}
    return out
