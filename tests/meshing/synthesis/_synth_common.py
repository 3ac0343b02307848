"""Design case of the synthesis tests: seed 001 Table 2 (docs/theory/example.md), pinion concave / gear convex."""

import math

ARCSEC = math.pi / (180.0 * 3600.0)
ETA = math.radians(6.0)      # path direction on the gear (the sign was lost in the OCR; both signs are tested)
A = 3.7                      # semi-major axis of the contact ellipse, mm
TE = 3.0 * ARCSEC            # magnitude of the parabolic TE over one mesh cycle
