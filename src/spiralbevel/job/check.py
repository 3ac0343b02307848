"""``spiralbevel check``: everything a run would reject, without the analyses."""

from __future__ import annotations


def check_design(spec) -> list:
    """Validate a design beyond its schema: the ISO blank, then the log-spiral pair or the face-milled cutters,
    settings, generated flanks (mean points) and synthesis. Raises the first error; returns the design warnings'
    texts of the blank."""
    from ..errors import DesignError
    from ..gearset.blank import blank_from_design
    from ..gearset.problems import with_design_keys

    blank = blank_from_design(spec)
    try:
        if spec.flank.kind == "log-spiral":
            from ..gearset.logspiral import design_pair

            design_pair(spec, blank)
        else:
            from ..gearset.facemilled import setup_flanks

            setup_flanks(spec, blank)
    except DesignError as err:
        raise with_design_keys(err, "gear_set" if spec.flank.kind == "log-spiral" else "face_milling") from err
    return list(getattr(blank, "warnings", ()))
