"""A stand-in for ``SynthesisResult`` in tests of the functions that read and replace a synthesized pinion's cutter,
settings and flank (``gearset.pinion_fillet``: ``raise_root``, ``lower_root``, ``fit_pinion_edge_radius``)."""

import dataclasses


@dataclasses.dataclass(frozen=True)
class Result:
    """The fields of a SynthesisResult that those functions read and replace."""

    pinion_cutter: object
    pinion_settings: object
    pinion_flank: object
