"""The 12/41, 35°, module 5, 30 mm face-milled design from basic data (the new user's design of the developed-pair
issue), shared by the tests that develop it."""

from _designs import basic_design


def design_12x41(z1: int = 12, *, shaft_angle=90, hand="RH", pressure_angle=20, flank="face-milled",
                 title=None) -> str:
    """The design file text, with ``z1`` pinion teeth (degrees and mm, as users write it); the other arguments vary
    the shaft angle, hand, normal pressure angle and flank kind of the same set."""
    return basic_design(z1, 41, module=5, face_width=30, mean_spiral_angle=35, shaft_angle=shaft_angle, hand=hand,
                        pressure_angle=pressure_angle, flank=flank, title=title)
