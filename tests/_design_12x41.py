"""The 12/41, 35°, module 5, 30 mm face-milled design from basic data (the new user's design of the developed-pair
issue), shared by the tests that develop it."""


def design_12x41(z1: int = 12) -> str:
    """The design file text, with ``z1`` pinion teeth (degrees and mm, as users write it)."""
    return f"""
[gear_set]
pinion_teeth = {z1}
gear_teeth = 41
shaft_angle = 90
module = 5
face_width = 30
normal_pressure_angle = 20
mean_spiral_angle = 35
pinion_hand = "RH"
[flank]
kind = "face-milled"
"""
