"""CSV files of CMM measurement grids and measured normal deviations.

Grid file (written by :func:`write_measurement_grid`): ``#`` comment lines (member, side, grid size, frame and sign
conventions), then one header row and one row per point::

    label,row,column,R_mm,h_mm,axial_mm,radius_mm,x_mm,y_mm,z_mm,nx,ny,nz[,deviation_mm]

Points and outward unit normals are in the member frame (axis +z, apex at the origin, body toward +z;
docs/conventions.md). Row 1 is at the toe, column 1 at the lower limit of the active flank; labels are
``F<row>P<column>``.

Measured-deviation file (read by :func:`read_measured_deviation`): any CSV with a ``label`` column (or ``row`` and
``column`` columns) and a ``deviation_mm`` column: the normal deviation in mm along the nominal outward normal,
**positive = material added** (the actual flank lies outside the nominal one, into the tooth space), negative =
material missing. The grid file with a filled-in deviation column is a valid input: its coordinate columns
(``x_mm, y_mm, z_mm``) and normals (``nx, ny, nz``), where present, must match the nominal grid's (within
:data:`POINT_TOL` mm and :data:`NORMAL_TOL_DEG`), and its first comment line, where present, must name the same member
and side, so a grid of another flank is refused even though its labels match. The file is read as UTF-8 text of at
most :data:`MAX_CSV_BYTES` bytes.
"""

from __future__ import annotations

import csv
import io
import math
import re
from pathlib import Path

import numpy as np

from ..errors import DesignError
from .atomic import atomic_write_text

__all__ = ["GRID_COLUMNS", "measurement_grid_csv", "write_measurement_grid", "read_measured_deviation",
           "POINT_TOL", "NORMAL_TOL_DEG", "MAX_CSV_BYTES"]

#: largest distance, mm, between a point of a measured file and the nominal point of the same label (a CMM reports
#: the nominal target or the probed point, which lies within the deviation, tenths of a millimetre at most)
POINT_TOL = 0.2
#: largest angle, deg, between a normal of a measured file and the nominal normal of the same label
NORMAL_TOL_DEG = 5.0
#: largest measured file read, bytes
MAX_CSV_BYTES = 8 << 20
_HEADER = re.compile(r"#\s*spiralbevel measurement grid:\s*(\w+)\s+(\w+)\s+flank")

GRID_COLUMNS = ("label", "row", "column", "R_mm", "h_mm", "axial_mm", "radius_mm", "x_mm", "y_mm", "z_mm",
                "nx", "ny", "nz")


def measurement_grid_csv(grid, deviation=None) -> str:
    """CSV text of a :class:`~spiralbevel.manufacturing.measurement.MeasurementGrid`.

    Parameters
    ----------
    grid : MeasurementGrid
    deviation : (n_face, n_profile) array_like, mm, optional
        Adds a ``deviation_mm`` column (positive = material added).
    """
    if deviation is not None:
        deviation = np.asarray(deviation, float)
        if deviation.shape != grid.shape or not np.all(np.isfinite(deviation)):
            raise DesignError.single("deviation", f"shape {deviation.shape}", f"finite values of shape {grid.shape}",
                                     "mm")
    buf = io.StringIO()
    buf.write(f"# spiralbevel measurement grid: {grid.member.value} {grid.side.value} flank, "
              f"{grid.shape[0]} x {grid.shape[1]} points (face x profile)\n")
    buf.write("# member frame: axis +z, apex at the origin; normals are outward unit normals (into the tooth space)\n")
    buf.write(f"# R, h: pitch-generatrix coordinate and height above the pitch line (pitch angle "
              f"{math.degrees(grid.pitch_angle):.6f} deg); row 1 = toe, column 1 = lower limit of the active flank\n")
    buf.write("# deviation_mm: normal deviation along the nominal normal, positive = material added\n")
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(GRID_COLUMNS + (("deviation_mm",) if deviation is not None else ()))
    for i, j in np.ndindex(grid.shape):
        p, n = grid.points[i, j], grid.normals[i, j]
        row = [grid.labels[i, j], int(grid.row[i, j]), int(grid.column[i, j])]
        row += [f"{v:.9f}" for v in (grid.R[i, j], grid.h[i, j], grid.axial[i, j], grid.radius[i, j], *p)]
        row += [f"{v:.12f}" for v in n]
        if deviation is not None:
            row.append(f"{deviation[i, j]:.9f}")
        w.writerow(row)
    return buf.getvalue()


def write_measurement_grid(path, grid, deviation=None) -> Path:
    """Write the grid (and optionally a deviation column) as CSV, atomically. Returns the path."""
    return atomic_write_text(path, measurement_grid_csv(grid, deviation))


def read_measured_deviation(path, grid) -> np.ndarray:
    """Read measured normal deviations for the points of ``grid``.

    Parameters
    ----------
    path : str or PathLike
        CSV with ``label`` (or ``row`` and ``column``) and ``deviation_mm`` columns; ``#`` lines are comments.
    grid : MeasurementGrid
        The nominal grid the measurement refers to.

    Returns
    -------
    (n_face, n_profile) float, mm
        Positive = material added.

    Raises
    ------
    DesignError
        Missing columns, unknown or duplicate points, points of the grid without a value, non-numeric values, a file
        of another member or side, coordinates or normals that are not the nominal grid's.
    """
    from .design_file import read_text_file

    text = read_text_file(path, f"measured file {Path(path).name}", MAX_CSV_BYTES)
    head = _HEADER.match(text.lstrip())
    if head and (head[1], head[2]) != (grid.member.value, grid.side.value):
        raise DesignError.single(f"{path}: header", f"{head[1]} {head[2]} flank",
                                 f"a measurement of the {grid.member.value} {grid.side.value} flank", "-",
                                 "the file is the grid of another flank")
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    reader = csv.DictReader(lines)
    fields = [f.strip() for f in (reader.fieldnames or [])]
    reader.fieldnames = fields
    if "deviation_mm" not in fields or not ("label" in fields or {"row", "column"} <= set(fields)):
        raise DesignError.single(f"{path}: columns", fields, "'deviation_mm' and 'label' (or 'row' and 'column')",
                                 "-")
    out = np.full(grid.shape, np.nan)
    try:
        records = list(reader)
    except csv.Error as err:
        raise DesignError.single(f"{path}", "(file)", "a CSV file", "-", f"malformed CSV: {err}") from err
    for k, rec in enumerate(records, start=2):
        try:
            if "label" in fields and rec.get("label"):
                i, j = grid.index_of(rec["label"])
            else:
                i, j = int(rec["row"]) - 1, int(rec["column"]) - 1
                if not (0 <= i < grid.shape[0] and 0 <= j < grid.shape[1]):
                    raise ValueError("row/column outside the grid")
            value = float(rec["deviation_mm"])
        except (ValueError, TypeError) as err:
            raise DesignError.single(f"{path}: data line {k}", _shown(rec), "a grid point with a numeric "
                                     "deviation_mm", "mm", str(err)) from err
        try:
            _check_geometry(rec, fields, grid, i, j, path)
        except (ValueError, TypeError) as err:
            if isinstance(err, DesignError):
                raise
            raise DesignError.single(f"{path}: data line {k}", _shown(rec), "numeric coordinates and normals",
                                     "mm", str(err)) from err
        if not math.isfinite(value):
            raise DesignError.single(f"{path}: deviation_mm of {grid.labels[i, j]}", value, "finite", "mm")
        if np.isfinite(out[i, j]):
            raise DesignError.single(f"{path}: point {grid.labels[i, j]}", "twice", "each point once", "-")
        out[i, j] = value
    missing = grid.labels[~np.isfinite(out)]
    if missing.size:
        raise DesignError.single(f"{path}: points", ", ".join(missing[:10]) + (" ..." if missing.size > 10 else ""),
                                 "a deviation for every grid point", "mm", "missing points")
    return out


def _shown(rec) -> str:
    """A record as shown in a message (cut to 120 characters)."""
    text = ", ".join(f"{k}={v}" for k, v in rec.items())
    return text if len(text) <= 120 else text[:120] + "..."


def _check_geometry(rec, fields, grid, i, j, path) -> None:
    """Coordinates and normals of a record, where the file has them, against the nominal point ``(i, j)``."""
    label = grid.labels[i, j]
    if {"x_mm", "y_mm", "z_mm"} <= set(fields):
        p = np.array([float(rec["x_mm"]), float(rec["y_mm"]), float(rec["z_mm"])])
        dist = float(np.linalg.norm(p - grid.points[i, j]))
        if not dist <= POINT_TOL:
            raise DesignError.single(f"{path}: x_mm, y_mm, z_mm of {label}", [round(float(v), 6) for v in p],
                                     f"within {POINT_TOL} mm of the nominal point "
                                     f"{[round(float(v), 4) for v in grid.points[i, j]]}", "mm",
                                     f"{dist:.4g} mm away: a measurement of another flank or design?")
    if {"nx", "ny", "nz"} <= set(fields):
        n = np.array([float(rec["nx"]), float(rec["ny"]), float(rec["nz"])])
        norm = float(np.linalg.norm(n))
        cos = float(n @ grid.normals[i, j]) / norm if norm > 0 and math.isfinite(norm) else -2.0
        if not cos >= math.cos(math.radians(NORMAL_TOL_DEG)):
            raise DesignError.single(f"{path}: nx, ny, nz of {label}", [round(float(v), 6) for v in n],
                                     f"within {NORMAL_TOL_DEG} deg of the nominal normal "
                                     f"{[round(float(v), 4) for v in grid.normals[i, j]]}", "-",
                                     "a measurement of another flank or design?")
