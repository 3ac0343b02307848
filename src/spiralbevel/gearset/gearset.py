"""``GearSet``: one gear pair assembled once from a design; each analysis returns a result object."""

from __future__ import annotations

from functools import cached_property
from pathlib import Path

from ..conventions import Member, Side
from ..errors import DesignError

__all__ = ["GearSet"]

#: pair sides of a face-milled pair: (pinion side, gear side)
PAIR_SIDES = {"drive": (Side.CONCAVE, Side.CONVEX), "coast": (Side.CONVEX, Side.CONCAVE)}


class GearSet:
    """A spiral bevel gear pair: blank, cutters, machine settings and flanks of both members and sides.

    Built from a design (:meth:`from_design`, :meth:`from_dict`, :meth:`from_basic_data`); the parts are computed on
    first use and kept. Each analysis method returns a result object with ``.plot()``, ``.to_dict()`` (the names and
    values of the matching report.json section, from the same function the main job uses), a concise ``repr`` and
    ``_repr_html_`` for notebooks. Units: mm, degrees for angles and rotations, arcsec for transmission errors,
    N/mm^2 for pressures and stresses, N m for torques.

    Parameters
    ----------
    design : DesignFile
        A validated design (:func:`spiralbevel.load_design`).

    Examples
    --------
    >>> import spiralbevel as sb
    >>> gs = sb.GearSet.from_basic_data(pinion_teeth=23, gear_teeth=65, module=4.0, face_width=30.0,
    ...                                 mean_spiral_angle=35.0)           # doctest: +SKIP
    >>> gs.tca("drive").peak_to_peak_arcsec                                # doctest: +SKIP
    """

    def __init__(self, design):
        from ..io.design_schema import DesignFile

        if not isinstance(design, DesignFile):
            raise DesignError.single("design", type(design).__name__, "a DesignFile (GearSet.from_design / "
                                     "from_dict / from_basic_data)", "-")
        self.design = design

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_design(cls, path=None) -> "GearSet":
        """Gear set of a design file (TOML; default: the bundled default design).

        Parameters
        ----------
        path : str or Path, optional
            A design file, or the name of a bundled design (``spiralbevel.io.design_file.bundled_designs()``).
        """
        from ..io.design_file import bundled_designs, load_design

        if path is not None and not Path(path).exists() and str(path) in bundled_designs():
            path = bundled_designs()[str(path)]
        return cls._checked(load_design(path))

    @classmethod
    def from_dict(cls, data: dict) -> "GearSet":
        """Gear set of a design given as a dict with the sections and keys of a design file (degrees, mm)."""
        from ..io.design_file import validate_design

        if not isinstance(data, dict):
            raise DesignError.single("design", type(data).__name__, "a dict of design-file sections", "-")
        spec = validate_design(data)
        return cls._checked(spec)

    @classmethod
    def from_basic_data(cls, *, pinion_teeth: int, gear_teeth: int, face_width: float, mean_spiral_angle: float,
                        module: float | None = None, outer_pitch_diameter: float | None = None,
                        kind: str = "face-milled", title: str = "spiral bevel gear set", **gear_set) -> "GearSet":
        """Gear set from the basic data of an ISO 23509 blank (the ``[gear_set]`` keys of a design file).

        Parameters
        ----------
        pinion_teeth, gear_teeth : int
        face_width : float, mm
        mean_spiral_angle : float, deg
        module : float, mm, optional
            Outer transverse module (or ``outer_pitch_diameter``).
        outer_pitch_diameter : float, mm, optional
        kind : {"face-milled", "log-spiral"}
            Flank form.
        title : str
        **gear_set
            Any other ``[gear_set]`` key: ``shaft_angle`` (deg), ``normal_pressure_angle`` (deg),
            ``coast_pressure_angle`` (deg), ``pinion_hand`` ("RH"/"LH"), ``cutter_radius`` (mm), ``depth`` (dict).
        """
        g = dict(pinion_teeth=pinion_teeth, gear_teeth=gear_teeth, face_width=face_width,
                 mean_spiral_angle=mean_spiral_angle, **gear_set)
        if module is not None:
            g["module"] = module
        if outer_pitch_diameter is not None:
            g["outer_pitch_diameter"] = outer_pitch_diameter
        return cls.from_dict({"title": title, "gear_set": g, "flank": {"kind": kind}})

    @classmethod
    def _checked(cls, spec) -> "GearSet":
        gs = cls(spec)
        gs.blank   # noqa: B018  # bad basic data fails here, naming the design-file key
        return gs

    # ------------------------------------------------------------------ parts
    @property
    def kind(self) -> str:
        """``"face-milled"`` or ``"log-spiral"``."""
        return self.design.flank.kind

    @property
    def title(self) -> str:
        return self.design.title

    @cached_property
    def blank(self):
        """The ISO 23509 blank (:class:`~spiralbevel.design.blank_result.BevelBlank`)."""
        from .blank import blank_from_design

        return blank_from_design(self.design)

    @cached_property
    def _setups_synthesis(self):
        from .facemilled import setup_flanks

        self._require("face-milled", "cutters, machine settings and generated flanks")
        if self.is_hypoid:   # basic settings at each member's mean cone distance, pinion by hypoid local synthesis
            from .hypoid import setup_hypoid_flanks

            return setup_hypoid_flanks(self.design, self.blank, with_synthesis=True)
        return setup_flanks(self.design, self.blank, with_synthesis=True)

    @property
    def is_hypoid(self) -> bool:
        """True for a hypoid pair (``gear_set.hypoid_offset`` != 0: ISO 23509 Method 1 blank, offset kinematics)."""
        return float(self.blank.a) != 0.0

    @property
    def setups(self) -> dict:
        """{(Member, Side): FlankSetup} of a face-milled pair: cutter, machine settings, generated flank, source."""
        return self._setups_synthesis[0]

    @property
    def synthesis(self) -> dict:
        """{side name: synthesis result} of the sides whose pinion flank was synthesized (face-milled)."""
        return self._setups_synthesis[1]

    @cached_property
    def logspiral_pair(self):
        """The :class:`~spiralbevel.design.logspiral_pair.LogSpiralPair` of a log-spiral design."""
        from .logspiral import design_pair

        self._require("log-spiral", "the log-spiral pair")
        return design_pair(self.design, self.blank)

    def flank(self, member, side):
        """The flank of ``member`` ("pinion"/"gear") and ``side`` ("convex"/"concave") in its member frame: a
        :class:`~spiralbevel.generation.flank.ToothFlank` (face-milled) or a placed log-spiral flank."""
        m, s = Member(member), Side(side)
        if self.kind == "log-spiral":
            return self.logspiral_pair.flank(m, s)
        return self.setups[(m, s)].flank

    def cutter(self, member, side):
        """The head cutter of a face-milled flank (:class:`~spiralbevel.machine.cutter.HeadCutter`)."""
        return self.setups[(Member(member), Side(side))].cutter

    def settings(self, member, side):
        """The machine settings of a face-milled flank (:class:`~spiralbevel.machine.settings.MachineSettings`)."""
        return self.setups[(Member(member), Side(side))].settings

    def pair(self, side: str = "drive"):
        """The pinion and gear flanks of one side phased for meshing
        (:class:`~spiralbevel.meshing.pair.MeshingPair`)."""
        from ..meshing.pair import meshing_pair

        s1, s2 = PAIR_SIDES[_side_name(side)]
        if self.is_hypoid:
            return self._hypoid_pair(side)
        return meshing_pair(self.setups[(Member.PINION, s1)].flank, self.setups[(Member.GEAR, s2)].flank, self.blank)

    def grids(self, n_face: int | None = None, n_profile: int | None = None) -> dict:
        """Flank geometry on a face x profile grid (default ``[output] grid``): {(Member, Side): FlankGeometry}."""
        nf, npf = self.design.output.grid
        key = (n_face or nf, n_profile or npf)
        cache = self.__dict__.setdefault("_grids", {})
        if key not in cache:
            if self.kind == "log-spiral":
                from .logspiral import flank_grids

                cache[key] = flank_grids(self.logspiral_pair, *key)
            else:
                cache[key] = {k: st.flank.grid(*key) for k, st in self.setups.items()}
        return cache[key]

    # ------------------------------------------------------------------ analyses
    def machine_summary(self):
        """Cutters, machine settings and the achieved flank data of all four flanks (:class:`MachineSummary`)."""
        from .facemilled import flank_report
        from .results import MachineSummary

        self._require("face-milled", "machine_summary() (log-spiral flanks are not cut by a face-milling cutter)")
        flanks, machines = flank_report(self.setups, self.blank, self.design)
        if not self.is_hypoid:
            from .slot_check import slot_report

            slot_report(self.design, self.blank, self.setups, flanks)   # each cutter's opposite blade (as the job)
            from .root_cone import root_cone_report

            root_cone_report(self.design, self.setups, flanks)   # each generated root against the root cone
            from .fillet_top import fillet_top_report
            from .tca import side_tca

            tca = {n: side_tca(self.blank, self.setups, n, n_positions=self.design.tca.positions)[1]
                   for n in ("drive", "coast")}
            fillet_top_report(self.design, self.blank, self.setups, flanks, tca)   # each fillet (as the job)
        return MachineSummary(flanks, machines)

    def tca(self, side: str = "drive", misalignment=None, positions: int | None = None):
        """Tooth contact analysis of one side over one mesh cycle (:class:`TCA`).

        Parameters
        ----------
        side : {"drive", "coast"}
            Face-milled: drive = pinion concave on gear convex. Log-spiral: ``"convex-concave"`` or
            ``"concave-convex"`` (pinion side first).
        misalignment : Misalignment or dict, optional
            :class:`~spiralbevel.meshing.misalignment.Misalignment`, or a dict of its fields in mm and degrees
            (``{"pinion_axial": 0.05, "shaft_angle": 0.05}``).
        positions : int, optional
            Pinion positions over the cycle (default ``[tca] positions``; 21 for a log-spiral pair, as the main job).
        """
        from .results import TCA

        mis = _misalignment(misalignment)
        if self.kind != "log-spiral":
            _side_name(side)
        if self.kind == "log-spiral":
            from .logspiral_tca import LOGSPIRAL_TCA_POSITIONS, logspiral_side_tca

            n = positions or LOGSPIRAL_TCA_POSITIONS
            if mis is not None:
                raise DesignError.single("misalignment", misalignment, "None for a log-spiral pair", "-",
                                         "the TCA of a misaligned log-spiral pair is reported by the mismatch study "
                                         "([crowning] section), not by GearSet.tca")
            res, section = logspiral_side_tca(self.logspiral_pair, side, n_positions=n)
            return TCA(side, res, section, None)
        from .tca import side_tca

        side = _side_name(side)
        n = positions or self.design.tca.positions
        res, section, outline = side_tca(self.blank, self.setups, _side_name(side), n_positions=n,
                                         misalignment=mis, grids=self.grids(),
                                         pair=self._hypoid_pair(side) if self.is_hypoid else None,
                                         events=mis is None and not self.is_hypoid)   # as the job's report
        if mis is None:   # the developed-pair checks, as the main job reports them
            from .run_facemilled import add_te_level, iso_contact_ratio, pinion_settings_given, tca_side_checks

            section["checks"] = tca_side_checks(res, side, self.synthesis, self.blank.z1,
                                                pinion_settings_given(self.design, side),
                                                self.design.synthesis is None)
            add_te_level(section, res, self.synthesis, _side_name(side), self.blank.z1)
            if not self.is_hypoid:
                iso_contact_ratio(section, self.blank, side)
        return TCA(_side_name(side), res, section, outline)

    def sensitivity(self, side: str = "drive", positions: int | None = None):
        """TE level and contact shift under each small misalignment of the main job's study (:class:`Sensitivity`)."""
        from .results import Sensitivity
        from .tca import misalignment_sensitivity

        self._require("face-milled", "sensitivity() (the log-spiral mismatch study runs from a [crowning] section)")
        return Sensitivity(misalignment_sensitivity(self.blank, self.setups, _side_name(side),
                                                    n_positions=positions or self.design.tca.positions,
                                                    pair=self._hypoid_pair(side) if self.is_hypoid else None))

    def ltca(self, torque="approach", side: str | None = None, positions: int | None = None):
        """Loaded tooth contact analysis over one mesh cycle (:class:`LTCA`).

        Parameters
        ----------
        torque : float or "approach"
            Gear torque, N m; ``"approach"``: the torque at which the approach at the mean point is 0.00635 mm.
        side : {"drive", "coast"}, optional
            Default ``[ltca] side``.
        positions : int, optional
            Mesh positions (default ``[ltca] positions``).

        Returns
        -------
        LTCA

        Notes
        -----
        Options not given here come from the design's ``[ltca]`` section (or its defaults).
        """
        from ..io.design_schema import LTCASpec
        from .ltca import run_ltca
        from .results import LTCA

        self._require("face-milled", "ltca() (the loaded TCA of a log-spiral pair is not implemented)")
        base = self.design.ltca or LTCASpec()
        upd = {"torque": torque}
        if side is not None:
            upd["side"] = _side_name(side)
        if positions is not None:
            upd["positions"] = positions
        lt = LTCASpec.model_validate({**base.model_dump(), **upd})
        if self.is_hypoid:   # FE segments placed by the offset kinematics of the synthesized pair
            from .hypoid_ltca import hypoid_fe_ltca

            res, section = hypoid_fe_ltca(self, lt)
        else:
            res, section = run_ltca(self.blank, self.setups, lt)
        return LTCA(lt.side, res, section)

    def easeoff(self):
        """Ease-off of the drive and coast pinion flanks against the conjugates of the gear flanks
        (:class:`EaseOff`)."""
        from .inspection import easeoff_maps
        from .results import EaseOff

        self._require("face-milled", "easeoff()")
        if self.is_hypoid:
            from .hypoid import hypoid_easeoff_maps

            pairs = {name: self._hypoid_pair(name) for name in PAIR_SIDES if name in self.synthesis}
            section, _, maps = hypoid_easeoff_maps(self.setups, pairs)
            return EaseOff(section, maps)
        section, _, maps = easeoff_maps(self.blank, self.setups, None, False, return_maps=True)
        return EaseOff(section, maps)

    def measurement_grid(self):
        """9 x 5 nominal CMM grids with outward normals of all four flanks (:class:`MeasurementGrids`)."""
        from .inspection import measurement_grids
        from .results import MeasurementGrids

        self._require("face-milled", "measurement_grid()")
        return MeasurementGrids(measurement_grids(self.setups))

    def rate(self):
        """ISO 10300 Method B1 load capacity of the design's ``[rating]`` section (:class:`Rating`)."""
        from .rating import rating_from_design, rating_section
        from .results import Rating

        if self.design.rating is None:
            raise DesignError.single("rating", "<missing>", "a [rating] section", "",
                                     "rate() needs the operating data of a [rating] section (torque or power, speed, "
                                     "materials, lubricant)")
        res = rating_from_design(self.design, self.blank)
        return Rating(res, rating_section(res))

    # ------------------------------------------------------------------ files
    def to_stl(self, directory) -> list[Path]:
        """STL of one tooth and of the whole gear for each member into ``directory`` (the files of the main job:
        ``pinion_tooth.stl``, ``pinion.stl``, ``gear_tooth.stl``, ``gear.stl``; face-milled teeth with their
        generated fillets), on the ``[output] grid``. Returns the paths written."""
        return self._cad_files(directory, "stl")

    def to_step(self, directory, whole_gear: bool = True) -> list[Path]:
        """STEP solids (extra ``cad``) of one tooth of each member into ``directory`` (``pinion_tooth.step``,
        ``gear_tooth.step``) and with ``whole_gear`` the whole members (``pinion.step``, ``gear.step``: the tooth
        placed z times and fused with the body, the slow part). Returns the paths written."""
        return self._cad_files(directory, "step", whole_gear)

    def report(self, directory, progress: bool = False):
        """Write the main job's report directory (report.json, plots, CSV, CAD files as the design's ``[output]``
        asks) into ``directory``, whole or not at all. Returns the :class:`~spiralbevel.gearset.run.RunSummary`."""
        from .run import write_run

        return write_run(self, directory, progress=progress)

    # ------------------------------------------------------------------ helpers
    def _cad_files(self, directory, fmt, whole_gear=True):
        from . import outputs

        out = Path(directory)
        out.mkdir(parents=True, exist_ok=True)
        tooth, teeth, cad = self._tooth_grids()
        names = (outputs.stl_files(tooth, teeth, out, cad=cad) if fmt == "stl"
                 else outputs.step_files(tooth, out, teeth=teeth if whole_gear else None, cad=cad))
        return [out / n for n in names]

    def _tooth_grids(self):
        """({member: (convex, concave) grids of one tooth}, {member: z}, CAD grids with fillets or None): the teeth
        the job writes as STL and STEP."""
        nf, npf = self.design.output.grid
        if self.kind == "log-spiral":
            from .logspiral import MEMBERS, tooth_grids

            pair = self.logspiral_pair
            tooth = {m: tooth_grids(pair, self.grids(), m) for m in MEMBERS}
            return tooth, {Member.PINION: pair.pinion.teeth, Member.GEAR: pair.gear.teeth}, None
        from . import facemilled as fm
        from . import outputs

        grids = self.grids()
        tooth = {}
        for m in fm.MEMBERS:
            rot = fm.tooth_rotation(self.blank, self.setups, m)
            cx, cc = grids[(m, Side.CONVEX)], grids[(m, Side.CONCAVE)]
            tooth[m] = ((cx.points, cx.normals), fm.rotate_grid(cc.points, cc.normals, rot))
        cad, _ = outputs.cad_teeth(self.design, self.blank, self.setups, nf, npf)
        return tooth, {Member.PINION: self.blank.z1, Member.GEAR: self.blank.z2}, cad

    def _hypoid_pair(self, side):
        """The synthesized hypoid pair of ``side`` with the offset kinematics (:func:`.hypoid.hypoid_pair`)."""
        from .hypoid import hypoid_pair

        if side not in self.synthesis:
            raise DesignError.single("synthesis.sides", sorted(self.synthesis), f"a list with '{side}'", "-",
                                     "a hypoid pair meshes through its local synthesis: the pinion flank of this side "
                                     "was not synthesized")
        return hypoid_pair(self.synthesis[side])

    def _no_hypoid(self, what):
        """Stop an analysis that assembles the pair with intersecting axes when the pair is a hypoid."""
        if self.is_hypoid:
            from .run_hypoid import NOT_AVAILABLE

            raise DesignError.single("gear_set.hypoid_offset", float(self.blank.a), "0 for " + what, "mm",
                                     f"{what} is {NOT_AVAILABLE} (it assembles the pair with intersecting axes)")

    def _require(self, kind, what):
        if self.kind != kind:
            raise DesignError.single("flank.kind", self.kind, kind, "-", f"{what} needs a {kind} design")

    def __repr__(self) -> str:
        b = self.design.gear_set
        return (f"GearSet({self.title!r}, {self.kind}, z = {b.pinion_teeth}/{b.gear_teeth}, "
                f"beta_m = {b.mean_spiral_angle:g} deg, b = {b.face_width:g} mm)")

    def _repr_html_(self) -> str:
        from .results import html_table

        b = self.design.gear_set
        return html_table(f"GearSet: {self.title}", {
            "flank kind": self.kind, "teeth (pinion / gear)": f"{b.pinion_teeth} / {b.gear_teeth}",
            "mean spiral angle_deg": b.mean_spiral_angle, "face width_mm": b.face_width,
            "shaft angle_deg": b.shaft_angle, "pinion hand": b.pinion_hand})


def _side_name(side: str) -> str:
    if side not in PAIR_SIDES:
        raise DesignError.single("side", side, "'drive' or 'coast'", "-")
    return side


def _misalignment(mis):
    """A Misalignment from None, a Misalignment or a dict of its fields in mm and degrees."""
    import math

    from ..meshing.misalignment import Misalignment

    if mis is None or isinstance(mis, Misalignment):
        return mis
    if isinstance(mis, dict):
        known = {"pinion_axial", "gear_axial", "offset", "shaft_angle"}
        bad = set(mis) - known
        if bad:
            raise DesignError.single("misalignment", sorted(bad), ", ".join(sorted(known)), "mm / deg")
        kw = dict(mis)
        if "shaft_angle" in kw:
            kw["shaft_angle"] = math.radians(kw["shaft_angle"])
        return Misalignment(**kw)
    raise DesignError.single("misalignment", type(mis).__name__, "None, a Misalignment or a dict", "-")
