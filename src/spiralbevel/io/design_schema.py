"""Design-file schema (TOML, validated by pydantic with ``extra="forbid"``).

Angles are degrees or DMS strings (``"22°30'"``); lengths are mm. Each field carries its unit in
``json_schema_extra={"unit": ...}`` so that error messages can name it.
"""

from __future__ import annotations

from typing import Annotated, Literal, Optional, Union

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, field_validator, model_validator

from .angles import parse_angle_deg

__all__ = ["Angle", "GearSetSpec", "DepthSpec", "FlankSpec", "ManufacturingSpec", "OutputSpec", "CutterSpec",
           "MachineSpec", "FlankMachineSpec", "FaceMillingSpec", "SynthesisSpec", "TCASpec", "LTCASpec",
           "CrowningSpec", "MisalignmentSpec", "RatingSpec", "DesignFile"]

Angle = Annotated[float, BeforeValidator(parse_angle_deg)]
GridCount = Annotated[int, Field(ge=3, le=401)]


def _f(default=..., unit: str = "-", **kw):
    return Field(default, json_schema_extra={"unit": unit}, **kw)


class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, validate_default=True)


class DepthSpec(_Model):
    """Depthwise proportions and taper (ISO 23509 Method 0)."""

    taper: Literal["given", "standard", "uniform", "duplex", "trl"] = _f(
        "duplex", description="depthwise taper system (trl: tilted root line)")
    mean_addendum_factor: Optional[float] = _f(None, ge=0.0, le=1.0, description="c_ham; default 0.21 + 0.29/u^2")
    depth_factor: float = _f(2.0, gt=0.0, le=4.0, description="k_d, mean working depth / mean normal module")
    clearance_factor: float = _f(0.125, ge=0.0, le=1.0, description="k_c")
    thickness_factor: float = _f(0.0, ge=-0.5, le=0.5, description="k_t")
    dedendum_angles: Optional[tuple[Angle, Angle]] = _f(
        None, unit="deg", description="theta_f1, theta_f2 for taper = 'given' (uniform clearance)")
    gear_addendum_dedendum_angles: Optional[tuple[Angle, Angle]] = _f(
        None, unit="deg", description="theta_a2, theta_f2 for taper = 'given' (ISO data type II)")
    backlash: float = _f(0.0, unit="mm", ge=0.0, le=2.0, description="outer normal backlash j_en")

    @model_validator(mode="after")
    def _given_angles(self):
        if self.taper == "given" and self.dedendum_angles is None and self.gear_addendum_dedendum_angles is None:
            raise ValueError(
                "taper = 'given' needs dedendum_angles = [theta_f1, theta_f2] or "
                "gear_addendum_dedendum_angles = [theta_a2, theta_f2] (deg)")
        return self


class GearSetSpec(_Model):
    """Basic data of the gear set."""

    pinion_teeth: int = _f(..., ge=5, le=200, description="z1")
    gear_teeth: int = _f(..., ge=5, le=500, description="z2")
    shaft_angle: Angle = _f(90.0, unit="deg", gt=10.0, lt=170.0, description="Sigma")
    module: Optional[float] = _f(None, unit="mm", gt=0.0, le=100.0, description="outer transverse module m_et")
    outer_pitch_diameter: Optional[float] = _f(None, unit="mm", gt=0.0, le=5000.0, description="d_e2 of the gear")
    face_width: float = _f(..., unit="mm", gt=0.0, le=1000.0, description="b")
    normal_pressure_angle: Angle = _f(20.0, unit="deg", gt=5.0, lt=45.0, description="alpha_n (drive side)")
    coast_pressure_angle: Optional[Angle] = _f(None, unit="deg", gt=5.0, lt=45.0, description="alpha_n coast side")
    mean_spiral_angle: Angle = _f(..., unit="deg", gt=0.0, lt=60.0, description="beta_m (magnitude)")
    pinion_hand: Literal["RH", "LH"] = _f("RH", description="hand of spiral of the pinion; the gear is opposite")
    cutter_radius: float = _f(114.3, unit="mm", gt=0.0, le=1000.0, description="r_c0 nominal cutter radius")
    hypoid_offset: float = _f(0.0, unit="mm", ge=-1000.0, le=1000.0, description="a, ISO 23509 sign: > 0 when the "
                               "pinion offset follows the wheel's hand of spiral; != 0: ISO 23509 Method 1 (Gleason) "
                               "blank, face-milled flanks only")
    blank_method: Optional[Literal[0, 1, 2, 3]] = _f(
        None, description="ISO 23509 pitch-cone method: 0 (no offset), 1 (Gleason, hypoid); 2 and 3 (Oerlikon, "
        "Klingelnberg) are not implemented; default from hypoid_offset (0 -> 0, else 1)")
    limit_pressure_angle_factor: float = _f(0.0, ge=0.0, le=1.0, description="f_alim: share of the limit pressure "
                                            "angle taken into the generated flank angles (hypoid, ISO 23509)")
    gear_generation: Literal["generated", "formate"] = _f(
        "generated", description="the gear is generated (rolled) or Formate (non-generated, plunge cut: its flanks are "
        "the cutter surface); ISO 23509 Method 1 distinguishes the two; 'formate' needs a hypoid offset and "
        "face-milled flanks")
    depth: DepthSpec = DepthSpec()

    @model_validator(mode="after")
    def _size(self):
        if (self.module is None) == (self.outer_pitch_diameter is None):
            raise ValueError("give exactly one of module (mm) or outer_pitch_diameter (mm)")
        return self


class FlankSpec(_Model):
    """Which tooth flanks to build."""

    kind: Literal["log-spiral", "face-milled"] = _f("log-spiral")


class ManufacturingSpec(_Model):
    """Manufacturability checks."""

    die_direction: tuple[float, float, float] = _f((0.0, 0.0, 1.0), unit="-", description="forging die opening")
    ball_radius: float = _f(2.0, unit="mm", gt=0.0, le=50.0, description="ball-end tool radius")
    scallop_height: float = _f(0.005, unit="mm", gt=0.0, le=1.0, description="allowed scallop height")
    draft_angle: Angle = _f(0.0, unit="deg", ge=0.0, lt=45.0,
                            description="minimum forging draft angle: n_out . v_d <= -sin(draft_angle)")
    forging_relief: bool = _f(False, description="log-spiral: relieve the flanks that fail the draft (two feature "
                              "parameters of least added volume, docs/forging.md)")

    @field_validator("die_direction")
    @classmethod
    def _nonzero(cls, v):
        if not sum(c * c for c in v) > 0:
            raise ValueError("allowed: a non-zero direction vector (member frame)")
        return v


class OutputSpec(_Model):
    """What to compute and export."""

    grid: tuple[GridCount, GridCount] = _f((31, 15), description="face x profile grid per flank, 3..401 each")
    plots: bool = True
    stl: bool = True
    step: bool = False
    toolpaths: bool = True
    draft: bool = True


class CutterSpec(_Model):
    """A head cutter blade given explicitly (seed 001 Tables 4 and 5 vocabulary)."""

    point_radius: float = _f(..., unit="mm", gt=0.0, le=2000.0, description="R_h")
    blade_angle: Angle = _f(..., unit="deg", gt=0.0, lt=60.0, description="alpha_h (modified blade angle)")
    point_width: float = _f(..., unit="mm", gt=0.0, le=50.0, description="W")
    edge_radius: float = _f(..., unit="mm", gt=0.0, le=20.0, description="rho_h")
    profile_radius: Optional[float] = _f(None, unit="mm", gt=0.0, description="circular-arc blade profile radius")


class MachineSpec(_Model):
    """Cradle-machine settings given explicitly (signs: docs/conventions.md, 'Machine settings')."""

    radial_setting: float = _f(..., unit="mm", gt=0.0, le=2000.0, description="S_r")
    cradle_angle: Angle = _f(..., unit="deg", ge=-360.0, le=360.0, description="q")
    machine_root_angle: Angle = _f(..., unit="deg", gt=0.0, lt=90.0, description="gamma_m")
    machine_centre_to_back: float = _f(0.0, unit="mm", ge=-500.0, le=500.0, description="X_D")
    sliding_base: float = _f(0.0, unit="mm", ge=-500.0, le=500.0, description="X_B")
    blank_offset: float = _f(0.0, unit="mm", ge=-500.0, le=500.0, description="E_m")
    ratio_of_roll: float = _f(..., unit="-", gt=0.0, le=20.0, description="m_ic")
    modified_roll: tuple[float, ...] = _f((), unit="-", description="2C, 6D, 24E, 120F")
    blank_offset_poly: tuple[float, ...] = _f((), unit="mm", description="E_m(psi_c) coefficients e1, e2, ...")


class FlankMachineSpec(_Model):
    """Cutter and/or machine of one flank; what is left out is derived from the blank."""

    cutter: Optional[CutterSpec] = None
    machine: Optional[MachineSpec] = None


class FaceMillingSpec(_Model):
    """Face-milling: default cutters from the blank, basic settings by crown-gear generation, or given settings."""

    point_width: Optional[float] = _f(None, unit="mm", gt=0.0, le=50.0,
                                      description="W of derived cutters; default: slot width at the root")
    edge_radius: Optional[float] = _f(None, unit="mm", gt=0.0, le=20.0,
                                      description="rho_h of derived cutters; default 0.45 W")
    roll: Literal["pitch", "root"] = _f("pitch", description="ratio of roll of derived settings")
    pinion_convex: FlankMachineSpec = FlankMachineSpec()
    pinion_concave: FlankMachineSpec = FlankMachineSpec()
    gear_convex: FlankMachineSpec = FlankMachineSpec()
    gear_concave: FlankMachineSpec = FlankMachineSpec()


class SynthesisSpec(_Model):
    """Local synthesis of the pinion settings from the gear's (seed 001 §4; Litvin).

    Without this section a face-milled design is developed by default: both pinion sides synthesized, the path
    direction searched until the bearing stays inside the flanks, a semi-major axis of 0.15 b, an elastic approach
    of b/5827, a parabolic TE of 8 arcsec (docs/conventions.md, "Developed pair by default"). The section overrides
    those defaults key by key: a key it leaves out keeps the developed-pair default (not the field default listed
    here, which only documents the seed 001 values), and without `path_direction` the default search over path
    directions runs with the section's values (`te_magnitude = 12` alone develops both sides at 12 arcsec)."""

    sides: tuple[Literal["drive", "coast"], ...] = _f(
        ("drive",), description="sides whose pinion flank is synthesized; left out: both (a side with given pinion "
        "machine settings keeps them)")
    path_direction: Angle = _f(6.0, unit="deg", gt=-60.0, lt=60.0,
                               description="eta on the gear, from the profile direction, + toward the heel; left "
                               "out: the default search over path directions")
    semi_major_axis: float = _f(3.7, unit="mm", gt=0.0, le=50.0,
                                description="contact ellipse a at the mean point; left out: 0.15 b")
    te_magnitude: float = _f(3.0, unit="arcsec", gt=0.0, le=600.0,
                             description="parabolic TE over one mesh cycle; left out: 8 arcsec")
    approach: float = _f(0.00635, unit="mm", gt=0.0, le=0.1,
                         description="elastic approach of the ellipse; left out: b/5827")
    free: Literal["offset", "modified-roll", "fixed-blade"] = _f(
        "offset", description="settings solved for; left out: offset (the default search also tries the others)")
    motion_curve: Literal["parabolic", "cmc"] = _f(
        "parabolic", description="'cmc': predesigned fourth-order combined motion curve by multi-point control "
        "of the pinion blank offset (drive side)")
    control_points: int = _f(11, ge=3, le=61, description="multi-point control: number of control points")
    offset_interpolation: Literal["spline", "linear", "polynomial"] = _f(
        "spline", description="blank-offset law between control points")


class MisalignmentSpec(_Model):
    """Misalignment sizes of the sensitivity study (each applied alone; signs in docs/conventions.md)."""

    pinion_axial: float = _f(0.05, unit="mm", gt=0.0, le=5.0, description="Delta A1")
    gear_axial: float = _f(0.05, unit="mm", gt=0.0, le=5.0, description="Delta A2")
    offset: float = _f(0.05, unit="mm", gt=0.0, le=5.0, description="Delta E")
    shaft_angle: Angle = _f(0.05, unit="deg", gt=0.0, le=2.0, description="Delta gamma")


class CrowningSpec(_Model):
    """Log-spiral designs: crown the pinion so that the conjugate pair becomes mismatched (point contact), from
    targets at the mean point (docs/logspiral_mismatch.md)."""

    side: Literal["convex", "concave"] = _f("convex", description="pinion flank crowned (meets the other gear side)")
    semi_major_axis: float = _f(6.0, unit="mm", gt=0.0, le=50.0, description="contact ellipse a at the mean point")
    path_direction: Angle = _f(20.0, unit="deg", gt=-89.0, lt=89.0,
                               description="eta: path on the pinion flank from the profile toward the heel")
    te_level: float = _f(8.0, unit="arcsec", gt=0.0, le=600.0, description="parabolic TE at the cycle ends")
    approach: float = _f(0.00635, unit="mm", gt=0.0, le=0.1, description="elastic approach of the ellipse")
    misalignment: MisalignmentSpec = MisalignmentSpec()


class TCASpec(_Model):
    """Unloaded tooth contact analysis of a face-milled pair (both sides and the misalignment study)."""

    positions: int = _f(41, ge=11, le=4001,
                        description="pinion positions over one mesh cycle (transfer points are solved exactly "
                        "between them)")


class LTCASpec(_Model):
    """Loaded tooth contact analysis (seed 001 §4.3.2) of one side of a face-milled pair."""

    side: Literal["drive", "coast"] = _f("drive", description="pair side analysed")
    torque: Union[Literal["approach"], float] = _f(
        "approach", unit="N m", description="'approach' (the torque of a 0.00635 mm approach) "
                                          "or a gear torque 0 < T < 1e7")
    positions: int = _f(21, ge=5, le=201, description="mesh positions over one cycle")
    youngs_modulus: float = _f(206000.0, unit="N/mm^2", gt=1000.0, le=1e6, description="E of both members")
    poisson_ratio: float = _f(0.3, unit="-", gt=0.0, lt=0.5, description="nu of both members")
    flank_grid: tuple[GridCount, GridCount] = _f((15, 8), description="face x profile grid of the FE tooth model")
    contact_grid: tuple[GridCount, GridCount] = _f((21, 7),
                                                   description="potential contact points per pair: along x across")

    @field_validator("torque")
    @classmethod
    def _torque(cls, v):
        if not isinstance(v, str) and not (v > 0 and v < 1e7):
            raise ValueError("allowed: 'approach' or 0 < torque < 1e7 N m")
        return v


def _pair(v):
    """A number for both members, or a pair [pinion, gear]."""
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        return (v, v)
    return v


Pair = Annotated[tuple[float, float], BeforeValidator(_pair)]


class RatingSpec(_Model):
    """Load capacity rating, ISO 10300 Method B1 (pairs are [pinion, gear]; one number stands for both)."""

    pinion_torque: Optional[float] = _f(None, unit="N m", gt=0.0, le=1e7, description="T1, nominal pinion torque")
    power: Optional[float] = _f(None, unit="kW", gt=0.0, le=1e5, description="P, nominal power (instead of torque)")
    pinion_speed: float = _f(..., unit="1/min", gt=0.0, le=1e6, description="n1")
    application_factor: float = _f(1.0, ge=1.0, le=10.0, description="K_A")
    pitch_deviation: Optional[Pair] = _f(None, unit="um", description="single pitch deviation f_pt [pinion, gear]")
    accuracy_grade: Optional[int] = _f(None, ge=2, le=11, description="ISO 17485 grade (instead of pitch_deviation)")
    mounting: Literal["both-straddle", "one-cantilever", "both-cantilever"] = _f(
        "one-cantilever", description="bearing arrangement of pinion and gear")
    contact_pattern: Literal["full-load", "light-load", "sample-estimated"] = _f(
        "light-load", description="contact pattern verified under full load, under light test load, or on a sample "
        "set and estimated for full load")
    profile_crowning: Literal["low", "high"] = _f(
        "low", description="profile crowning of the pair: the distribution of the load over the contact lines "
        "(ISO 10300-2 load sharing factor)")
    cutter_edge_radius: Optional[Pair] = _f(None, unit="mm", description="rho_a0 [pinion, gear]; default: the "
                                            "edge radius of the cutter of each member's drive flank")
    youngs_modulus: float = _f(206000.0, unit="N/mm^2", gt=1000.0, le=1e6, description="E of both members")
    poisson_ratio: float = _f(0.3, unit="-", gt=0.0, lt=0.5, description="nu of both members")
    density: float = _f(7.86e-6, unit="kg/mm^3", gt=0.0, le=1e-4, description="rho of both members")
    material: Literal["case-hardened", "through-hardened"] = _f("case-hardened", description="steel class")
    sigma_Hlim: Pair = _f(..., unit="N/mm^2", description="allowable contact stress number [pinion, gear]")
    sigma_Flim: Pair = _f(..., unit="N/mm^2", description="allowable bending stress number [pinion, gear]")
    S_Hmin: float = _f(1.0, gt=0.0, le=10.0, description="minimum safety factor for pitting")
    S_Fmin: float = _f(1.3, gt=0.0, le=10.0, description="minimum safety factor for bending")
    load_cycles: Optional[float] = _f(None, gt=0.0, le=1e15, description="pinion load cycles N_L; default long life")
    hypoid_factor: Optional[float] = _f(None, gt=0.0, le=1.0, description="Z_Hyp, ISO 10300-2 hypoid factor of a "
                                        "hypoid pair (required with gear_set.hypoid_offset != 0, unused without)")
    oil_viscosity: float = _f(..., unit="mm^2/s", gt=0.0, le=1e5, description="nu_40 of the lubricant")
    flank_roughness: Pair = _f((8.0, 8.0), unit="um", description="Rz of the flanks [pinion, gear]")
    root_roughness: Pair = _f((16.0, 16.0), unit="um", description="Rz of the root fillets [pinion, gear]")

    @field_validator("pitch_deviation", "cutter_edge_radius", "sigma_Hlim", "sigma_Flim", "flank_roughness",
                     "root_roughness")
    @classmethod
    def _positive(cls, v):
        if v is not None and not all(x > 0 for x in v):
            raise ValueError("allowed: numbers > 0")
        return v

    @model_validator(mode="after")
    def _one_of(self):
        if (self.pinion_torque is None) == (self.power is None):
            raise ValueError("give exactly one of pinion_torque (N m) or power (kW)")
        if (self.pitch_deviation is None) == (self.accuracy_grade is None):
            raise ValueError("give exactly one of pitch_deviation [f_pt1, f_pt2] (um) or accuracy_grade (2 ... 11)")
        return self


class DesignFile(_Model):
    """A whole spiralbevel design file."""

    title: str = _f("spiral bevel gear set")
    gear_set: GearSetSpec
    flank: FlankSpec = FlankSpec()
    face_milling: FaceMillingSpec = FaceMillingSpec()
    synthesis: Optional[SynthesisSpec] = None
    tca: TCASpec = TCASpec()
    ltca: Optional[LTCASpec] = None
    crowning: Optional[CrowningSpec] = None
    rating: Optional[RatingSpec] = None
    manufacturing: ManufacturingSpec = ManufacturingSpec()
    output: OutputSpec = OutputSpec()

    @model_validator(mode="after")
    def _crowning_is_logspiral(self):
        if self.crowning is not None and self.flank.kind != "log-spiral":
            raise ValueError("[crowning] applies to flank.kind = 'log-spiral' only (face-milled pairs: [synthesis])")
        return self
