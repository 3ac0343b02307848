"""``spiralbevel check``: everything a run would reject, without the analyses."""

from __future__ import annotations


def check_design(spec) -> list:
    """Validate a design beyond its schema: the ISO blank, then the log-spiral pair or the face-milled cutters,
    settings, generated flanks (mean points) and synthesis. Raises the first error; returns the design warnings'
    texts of the blank."""
    from .blank import blank_from_design

    blank = blank_from_design(spec)
    if spec.flank.kind == "log-spiral":
        from .logspiral import design_pair

        design_pair(spec, blank)
    else:
        from .facemilled import setup_flanks

        setup_flanks(spec, blank)
    return list(getattr(blank, "warnings", ()))
