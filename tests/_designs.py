"""Design files from basic data for the tests (degrees and mm, as users write them), and the flanks they give."""

import warnings


def basic_design(z1: int, z2: int, *, module, face_width, mean_spiral_angle, shaft_angle=90, hand="RH",
                 pressure_angle=20, cutter_radius=None, flank="face-milled", title=None) -> str:
    """Design-file text of a gear set from basic data: ``[gear_set]`` and ``[flank]`` only (a test appends further
    sections); numbers written as given, so that a string keeps the digits a bench sample printed."""
    return "\n".join([
        "", *([f'title = "{title}"'] if title is not None else []),
        "[gear_set]",
        f"pinion_teeth = {z1}",
        f"gear_teeth = {z2}",
        f"shaft_angle = {shaft_angle}",
        f"module = {module}",
        f"face_width = {face_width}",
        f"normal_pressure_angle = {pressure_angle}",
        f"mean_spiral_angle = {mean_spiral_angle}",
        f'pinion_hand = "{hand}"',
        *([f"cutter_radius = {cutter_radius}"] if cutter_radius is not None else []),
        "[flank]",
        f'kind = "{flank}"',
        ""])


#: bench/bench_robustness.py 100 2, design 22 (16/87, beta 9.6 deg), as the bench writes it: the default synthesis'
#: coast candidates through the mean pitch point touch the pinion's fillet (gearset/depth_rescue.py)
DESIGN_16X87 = basic_design(16, 87, shaft_angle="66.706", module="1.723", face_width="24.312",
                            mean_spiral_angle="9.614", hand="LH", cutter_radius="61.48", title="sample")


def basic_setups(text):
    """``(spec, blank, {(member, side): FlankSetup})`` of a design-file text: the cutters, solved basic settings and
    generated flanks of all four member sides, no synthesis (design warnings silenced)."""
    from spiralbevel.gearset import facemilled as fm
    from spiralbevel.io.design_file import parse_design
    from spiralbevel.job.blank import blank_from_design

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        spec = parse_design(text)
        blank = blank_from_design(spec)
        return spec, blank, fm._basic_setups(spec, blank)


def developed(text):
    """``(spec, blank, setups, {side name: SynthesisResult})`` of a design-file text: the flanks of the job, the
    pinion synthesized by default (design warnings silenced)."""
    from spiralbevel.gearset import facemilled as fm
    from spiralbevel.io.design_file import parse_design
    from spiralbevel.job.blank import blank_from_design

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        spec = parse_design(text)
        blank = blank_from_design(spec)
        setups, synth = fm.setup_flanks(spec, blank, with_synthesis=True)
        return spec, blank, setups, synth


def coast_candidate_16x87(depth: float = 0.0):
    """``(blank, gear FlankSetup, SynthesisResult)``: the coast pinion of :data:`DESIGN_16X87` synthesized as the
    default search's candidate with the fewest positions off the flanks through the pitch point (path -55 deg,
    modified roll free, the default ellipse, approach and TE level), the mean contact point ``depth`` mm below the
    gear's pitch line."""
    import math

    from spiralbevel.conventions import Member
    from spiralbevel.gearset import facemilled as fm
    from spiralbevel.meshing import synthesis as syn
    from spiralbevel.meshing.tca_result import ARCSEC

    _, blank, basic = basic_setups(DESIGN_16X87)
    s1, s2 = fm.PAIR_SIDES["coast"]
    gear, pin = basic[(Member.GEAR, s2)], basic[(Member.PINION, s1)]
    b = float(blank.b2)
    res = syn.synthesize_pinion(gear.cutter, gear.settings, blank, side=s1, eta=math.radians(-55.0),
                                semi_major_axis=0.15 * b, te_magnitude=8.0 * ARCSEC,
                                approach=fm.DEFAULT_SYNTHESIS["approach_fraction"] * b, free=syn.FREE_MODIFIED_ROLL,
                                depth=depth, pinion_cutter_hint=pin.cutter, pinion_settings_hint=pin.settings)
    return blank, gear, res
