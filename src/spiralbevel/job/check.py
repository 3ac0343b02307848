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
            from ..gearset.blank import LOGSPIRAL_NO_OFFSET, require_no_offset
            from ..gearset.logspiral import design_pair

            require_no_offset(blank, "spiralbevel check on a log-spiral design", LOGSPIRAL_NO_OFFSET)
            design_pair(spec, blank)
        elif blank.a != 0.0:   # a hypoid: the four flanks as 'run' develops them (basic settings, hypoid synthesis)
            from ..gearset.hypoid import setup_hypoid_flanks

            setup_hypoid_flanks(spec, blank)
        else:
            from ..gearset.facemilled import setup_flanks

            setup_flanks(spec, blank)
    except DesignError as err:
        raise with_design_keys(err, "gear_set" if spec.flank.kind == "log-spiral" else "face_milling") from err
    return list(getattr(blank, "warnings", ()))


def schema_and_design_problems(err, text: str):
    """One round of ``spiralbevel check``: the schema problems of a design file together with the blank and flank
    problems of the rest of it.

    Parameters
    ----------
    err : DesignError
        What the schema validation of ``text`` raised.
    text : str
        The TOML text of the design file.

    Returns
    -------
    DesignError
        ``err``'s problems, followed by those :func:`check_design` finds on the design with every key named in them
        removed (so at its default), when that design is complete; otherwise ``err`` itself.
    """
    import tomllib

    from pydantic import ValidationError

    from ..errors import DesignError
    from ..io.design_schema import DesignFile

    try:
        data = tomllib.loads(text)
    except (tomllib.TOMLDecodeError, RecursionError):
        return err
    for p in err.problems:
        if not p.field:
            return err  # a problem of the whole file (too large, malformed): nothing else can be checked
        node, keys = data, p.field.split(".")
        while len(keys) > 1 and isinstance(node.get(keys[0]), dict):  # down to the table that holds the bad key
            node, keys = node[keys[0]], keys[1:]
        node.pop(keys[0], None)
    try:
        spec = DesignFile.model_validate(data)
        check_design(spec)
    except ValidationError:
        return err
    except DesignError as more:
        seen = {p.field for p in err.problems}
        extra = [p for p in more.problems if p.field not in seen]
        if not extra:
            return err
        return DesignError([*err.problems, *extra])
    return err
