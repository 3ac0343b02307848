"""Misalignment sweeps of a face-milled pair: TCA at every point of a grid of misalignments, in parallel with dask.
A hypoid pair is swept through its offset kinematics with the misalignments on top (``job/sweep_hypoid.py``).

The grid points are dealt into a few interleaved batches per worker (:func:`sweep_batch`, one dask task each: the
per-task overhead of the scheduler, a few ms, is paid a few times per worker instead of once per case). Each worker
process rebuilds the pair from the design (a pydantic model as JSON: small to ship) once and keeps it for all its
batches. With dask installed (extra ``dist``) the batches run on a pool of local processes that is kept for the next
sweep of the session, or on a cluster given by its scheduler address (``dask.distributed``, ``--scheduler
tcp://host:8786``); without dask, one after the other in this process.
"""

from __future__ import annotations

import functools
import itertools
import math
import os

import numpy as np

from ..errors import ConvergenceError, DesignError, MissingDependencyError, NoContactError

AXES = ("pinion_axial", "gear_axial", "offset", "shaft_angle")   # mm, mm, mm, deg (design units)
#: largest misalignment of each axis, design units: assembly errors of a bevel pair are tenths of a millimetre and
#: hundredths of a degree; beyond these the TCA of the aligned design's flanks says nothing useful
LIMITS = {"pinion_axial": 2.0, "gear_axial": 2.0, "offset": 2.0, "shaft_angle": 1.0}
UNITS = {"pinion_axial": "mm", "gear_axial": "mm", "offset": "mm", "shaft_angle": "deg"}
OPTIONS = {"pinion_axial": "--pinion-axial", "gear_axial": "--gear-axial", "offset": "--offset",
           "shaft_angle": "--shaft-angle"}
#: most values of one axis and most TCA runs of a sweep
MAX_VALUES, MAX_POINTS = 1000, 10000
_SCHEMES = ("tcp", "tls", "ws", "wss", "inproc", "ucx")


def parse_values(axis: str, text: str) -> list:
    """Values of one sweep axis from ``'v1,v2,...'`` or ``'start:stop:count'``, checked.

    Parameters
    ----------
    axis : str
        One of :data:`AXES`.
    text : str
        The option's text.

    Returns
    -------
    list of float
        In design units (mm, or deg for ``shaft_angle``).

    Raises
    ------
    DesignError
        Naming the option, the value, the allowed range and the unit: unreadable or non-finite numbers, values beyond
        :data:`LIMITS`, more than :data:`MAX_VALUES` values.
    """
    opt, unit, lim = OPTIONS[axis], UNITS[axis], LIMITS[axis]
    forms = "'v1,v2,...' or 'start:stop:count'"
    if len(text) > 20000:
        raise DesignError.single(opt, text[:40] + "...", forms, unit, "too long")
    try:
        if ":" in text:
            a, b, n = text.split(":")
            count = int(n)
            if not 1 <= count <= MAX_VALUES:
                raise DesignError.single(opt, text, f"1 <= count <= {MAX_VALUES}", "-", "count of 'start:stop:count'")
            lo, hi = float(a), float(b)
            values = [lo] if count == 1 else [lo + (hi - lo) * k / (count - 1) for k in range(count)]
        else:
            values = [float(v) for v in text.split(",")]
    except ValueError as err:
        raise DesignError.single(opt, text, forms, "-", "sweep values") from err
    if len(values) > MAX_VALUES:
        raise DesignError.single(opt, f"{len(values)} values", f"at most {MAX_VALUES} values", "-")
    for v in values:
        if not math.isfinite(v) or abs(v) > lim:
            raise DesignError.single(opt, v, f"finite, -{lim} <= value <= {lim}", unit, "sweep values")
    return values


def check_scheduler(address) -> None:
    """``None``, ``'sequential'`` or a dask scheduler address ``scheme://host:port`` (scheme tcp, tls, ws, wss;
    ``inproc://`` and ``ucx://`` addresses as dask writes them); else a :class:`DesignError` naming ``--scheduler``."""
    if address is None or address == "sequential":
        return
    allowed = "'sequential' or a dask scheduler address such as tcp://127.0.0.1:8786"
    scheme, sep, rest = str(address).partition("://")
    if not sep or scheme not in _SCHEMES or not rest or len(address) > 300 or any(c.isspace() for c in address):
        raise DesignError.single("--scheduler", address, allowed, "-")
    if scheme in ("inproc", "ucx"):
        return
    host, colon, port = rest.rstrip("/").rpartition(":")
    if not colon or not host or not port.isdigit() or not 1 <= int(port) <= 65535:
        raise DesignError.single("--scheduler", address, allowed, "-", "the address needs a host and a port "
                                 "1-65535")


@functools.lru_cache(maxsize=4)
def _pair(spec_json: str, side: str):
    """(pinion surface, gear surface, kinematics, gear (R, h) of (axial, radius), extra keywords of ``solve_tca``)."""
    from ..io.design_schema import DesignFile
    from ..meshing.generated_surface import phased_for_pair
    from ..meshing.kinematics import BevelPairKinematics
    from ..gearset.blank import blank_from_design
    from ..gearset.facemilled import PAIR_SIDES, setup_flanks

    spec = DesignFile.model_validate_json(spec_json)
    blank = blank_from_design(spec)
    if spec.flank.kind == "log-spiral":
        return _logspiral_pair(spec, blank, side)
    if float(blank.a) != 0.0:
        from .sweep_hypoid import hypoid_sweep_pair

        return hypoid_sweep_pair(spec, blank, side)
    setups = setup_flanks(spec, blank)
    s1, s2 = PAIR_SIDES[side]
    from ..conventions import Member

    c1, c2 = phased_for_pair(setups[(Member.PINION, s1)].flank, setups[(Member.GEAR, s2)].flank)
    start = np.r_[c1.reference_params, c2.reference_params, 0.0]
    return (c1, c2, BevelPairKinematics(blank.Sigma, blank.z1, blank.z2), setups[(Member.GEAR, s2)].flank.outline.Rh,
            {"start": start})


def default_side(spec) -> str:
    """``"drive"``, or for a log-spiral design with a ``[crowning]`` section the side of its crowned pinion flank."""
    from .facemilled import PAIR_SIDES

    if spec.flank.kind == "log-spiral" and spec.crowning is not None:
        return next(n for n, (s1, _) in PAIR_SIDES.items() if s1.value == spec.crowning.side)
    return "drive"


def check_logspiral_sweep(spec, side: str) -> None:
    """A log-spiral design can be swept only on the side of its crowned pinion flank: the exact pair is in line
    contact, which any misalignment turns into contact at a flank edge that the surface TCA does not follow.
    Raises :class:`DesignError` naming the design-file key otherwise."""
    from .facemilled import PAIR_SIDES

    if spec.crowning is None:
        raise DesignError.single("crowning", "absent", "a [crowning] section for a misalignment sweep of a log-spiral "
                                 "design", "-", "the exact log-spiral pair is in line contact, and any misalignment "
                                 "moves its contact onto a flank edge, which the surface TCA does not follow; a "
                                 "crowned pinion (see the bundled aviation_23x65_logspiral_forged) has point contact "
                                 "that can be swept")
    crowned = spec.crowning.side
    if PAIR_SIDES[side][0].value != crowned:
        other = next(n for n, (s1, _) in PAIR_SIDES.items() if s1.value == crowned)
        raise DesignError.single("--side", side, f"'{other}' (crowning.side = '{crowned}' is the crowned pinion flank)",
                                 "-", "the other side of a log-spiral design is the exact pair in line contact")


def _logspiral_pair(spec, blank, side: str):
    from ..conventions import Member
    from ..meshing.kinematics import BevelPairKinematics
    from .facemilled import PAIR_SIDES
    from .logspiral import design_pair
    from .logspiral_production import contact_surface, design_crowning

    check_logspiral_sweep(spec, side)
    pair = design_pair(spec, blank)
    crowning = design_crowning(spec, pair)
    s1, s2 = PAIR_SIDES[side]
    kin = BevelPairKinematics(pair.shaft_angle, pair.pinion.teeth, pair.gear.teeth)
    c1 = contact_surface(pair, Member.PINION, s1, crowning)
    c2 = contact_surface(pair, Member.GEAR, s2)
    p1 = pair.mean_point(Member.PINION, s1).point
    phi1_mean = -math.atan2(p1[1], p1[0])          # turns the pinion mean point onto the pitch line
    start = np.r_[c1.reference_params, c2.reference_params, -kin.ratio * phi1_mean]
    sd, cd = math.sin(pair.gear.pitch_angle), math.cos(pair.gear.pitch_angle)

    def rh(axial, radius):
        """Cone distance along the gear pitch cone and height above it, mm."""
        return radius * sd + axial * cd, radius * cd - axial * sd

    return c1, c2, kin, rh, {"start": start, "phi1_mean": phi1_mean}


def sweep_point(spec_json: str, side: str, values: tuple, n_positions: int = 41) -> dict:
    """TCA at one misalignment (values in design units: mm, mm, mm, deg). A plain function: a dask task."""
    from ..meshing.misalignment import Misalignment
    from ..meshing.tca import solve_tca

    c1, c2, kin, rh, extra = _pair(spec_json, side)
    kw = dict(zip(AXES, values))
    kw["shaft_angle"] = math.radians(kw["shaft_angle"])
    out = dict(zip(AXES, values))
    try:
        res = solve_tca(c1, c2, kin, misalignment=Misalignment(**kw), n_positions=n_positions, **extra)
    except (NoContactError, ConvergenceError, DesignError) as err:
        return dict(out, error=str(err))
    te = res.te_arcsec
    fin = np.isfinite(te)
    mid = n_positions // 2
    j = list(res.pairs).index(0)
    p = res.point2[mid, j]  # (R, h) depend on the axial position and radius only: any rotation about the axis
    R, h = rh(p[2], math.hypot(p[0], p[1]))
    return dict(out, peak_to_peak_arcsec=float(np.ptp(te[fin])) if np.any(fin) else None,
                edge_contact_positions=int(np.sum(res.edge_contact)), mean_contact_R_mm=float(R),
                mean_contact_h_mm=float(h))


def sweep_batch(spec_json: str, side: str, points: list, n_positions: int = 41) -> list:
    """:func:`sweep_point` for each misalignment of ``points`` (a list of value tuples, design units). A dask task."""
    return [sweep_point(spec_json, side, tuple(p), n_positions) for p in points]


#: batches per worker: enough that the last batches to finish leave a worker idle for a small share of the run (the
#: batches are handed out one at a time as workers free up), few enough that the scheduler's per-task cost (a few ms)
#: stays negligible
BATCHES_PER_WORKER = 8
#: fewest cases of a batch (below, the per-task cost would matter against a few TCAs)
MIN_BATCH = 8


def _batches(points, n_workers):
    """``points`` dealt into at most BATCHES_PER_WORKER * n_workers batches of nearly equal size (and at least
    MIN_BATCH cases where there are enough), interleaved: batch i holds points i, i + n, i + 2 n, ... so that every
    batch samples the whole grid and costs about the same (the costly cases near the edge of contact sit together in
    the grid). :func:`_merge` puts the results back in grid order."""
    n = max(1, min(len(points), BATCHES_PER_WORKER * max(1, n_workers), -(-len(points) // MIN_BATCH)))
    return [points[i::n] for i in range(n)]


def _merge(parts) -> list:
    """The records of :func:`_batches`' batches (in batch order) back in grid order."""
    n = len(parts)
    out = [None] * sum(len(p) for p in parts)
    for i, part in enumerate(parts):
        out[i::n] = part
    return out


@functools.lru_cache(maxsize=1)
def _local_pool(n_workers: int):
    """A process pool kept for the session (workers keep the pair built by :func:`_pair` between sweeps)."""
    import atexit
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    pool = ProcessPoolExecutor(n_workers, mp_context=multiprocessing.get_context("spawn"))
    atexit.register(pool.shutdown)  # stop the workers before the interpreter tears its modules down
    return pool


def _local_workers():
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)


def misalignment_sweep(spec, grid: dict, side: str = "drive", scheduler: str | None = None,
                       n_positions: int = 41) -> list:
    """TCA over the Cartesian product of misalignment values.

    Parameters
    ----------
    spec : DesignFile
        A face-milled design, or a log-spiral design with a ``[crowning]`` section (swept on the side of its crowned
        pinion flank, without the forging relief).
    grid : dict
        {axis: list of values} for axes in :data:`AXES` (mm, mm, mm, deg); missing axes are 0.
    side : {"drive", "coast"}
    scheduler : str, optional
        ``None``: dask's local processes when dask is installed, else sequential; ``"sequential"``: in this process;
        ``"tcp://host:port"``: a dask.distributed cluster (extra ``dist``).

    Returns
    -------
    list of dict
        One record per grid point: the misalignment values, TE peak-to-peak (arcsec), edge-contact positions, and the
        mean-position contact point on the gear in (R, h), mm.
    """
    bad = [k for k in grid if k not in AXES]
    if bad:
        raise DesignError.single("sweep axis", bad[0], ", ".join(AXES), "-")
    if side not in ("drive", "coast"):
        raise DesignError.single("--side", side, "'drive' or 'coast'", "-")
    if spec.flank.kind == "log-spiral":
        check_logspiral_sweep(spec, side)
    check_scheduler(scheduler)
    axes = []
    for k in AXES:
        values = [float(v) for v in grid.get(k, [0.0])]
        if not values or len(values) > MAX_VALUES:
            raise DesignError.single(OPTIONS[k], f"{len(values)} values", f"1 to {MAX_VALUES} values", "-")
        for v in values:
            if not math.isfinite(v) or abs(v) > LIMITS[k]:
                raise DesignError.single(OPTIONS[k], v, f"finite, -{LIMITS[k]} <= value <= {LIMITS[k]}", UNITS[k])
        axes.append(values)
    n_points = math.prod(len(a) for a in axes)
    if n_points > MAX_POINTS:
        raise DesignError.single("sweep grid", f"{n_points} TCA runs", f"at most {MAX_POINTS} runs", "-",
                                 "the product of the value counts of the four axes")
    points = list(itertools.product(*axes))
    spec_json = spec.model_dump_json()
    if scheduler == "sequential":
        return [sweep_point(spec_json, side, p, n_positions) for p in points]
    try:
        import dask
    except ImportError as err:
        if scheduler is None:
            return [sweep_point(spec_json, side, p, n_positions) for p in points]
        raise MissingDependencyError("dask[distributed]", "dist", "A distributed sweep") from err
    if scheduler is None:
        n_workers = _local_workers()
        tasks = [dask.delayed(sweep_batch)(spec_json, side, b, n_positions) for b in _batches(points, n_workers)]
        # chunksize 1: dask would otherwise hand out ready tasks in groups of 6, leaving a worker idle
        parts = dask.compute(*tasks, scheduler="processes", pool=_local_pool(n_workers), chunksize=1)
        return _merge(parts)
    try:
        from distributed import Client
    except ImportError as err:
        raise MissingDependencyError("dask[distributed]", "dist", "A distributed sweep") from err
    with Client(scheduler, timeout=20) as client:
        n_workers = sum(client.nthreads().values())
        tasks = [dask.delayed(sweep_batch)(spec_json, side, b, n_positions) for b in _batches(points, n_workers)]
        parts = dask.compute(*tasks, scheduler=client)
    return _merge(parts)
