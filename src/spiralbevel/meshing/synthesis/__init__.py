"""Local synthesis of the pinion machine settings at the mean contact point (seed 001 §4.3; Litvin's local
synthesis): the gear's mean point in the pair frame, the pinion's required principal curvatures from the contact-path
direction, the contact-ellipse size and the TE curvature, and the pinion cutter and machine settings that realise
them."""

from spiralbevel.meshing.synthesis.local import SynthesisResult, synthesize_pinion, te_parabola_coefficient
from spiralbevel.meshing.synthesis.machine_fit import (FREE_DEFAULT, FREE_FIXED_BLADE, FREE_MODIFIED_ROLL, FREE_OFFSET,
                                                       fit_settings)
from spiralbevel.meshing.synthesis.mean_contact import MeanContact, mean_contact, path_reference

__all__ = ["SynthesisResult", "synthesize_pinion", "te_parabola_coefficient", "MeanContact", "mean_contact",
           "path_reference", "FREE_DEFAULT", "FREE_OFFSET", "FREE_MODIFIED_ROLL", "FREE_FIXED_BLADE", "fit_settings"]
