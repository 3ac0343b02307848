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
material missing. Other columns are ignored, so the grid file with a filled-in deviation column is a valid input.
"""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import numpy as np

from ..errors import DesignError
from .atomic import atomic_write_text

__all__ = ["GRID_COLUMNS", "measurement_grid_csv", "write_measurement_grid", "read_measured_deviation"]

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
        Missing columns, unknown or duplicate points, points of the grid without a value, non-numeric values.
    """
    text = Path(path).read_text(encoding="utf-8")
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    reader = csv.DictReader(lines)
    fields = [f.strip() for f in (reader.fieldnames or [])]
    reader.fieldnames = fields
    if "deviation_mm" not in fields or not ("label" in fields or {"row", "column"} <= set(fields)):
        raise DesignError.single(f"{path}: columns", fields, "'deviation_mm' and 'label' (or 'row' and 'column')",
                                 "-")
    out = np.full(grid.shape, np.nan)
    for k, rec in enumerate(reader, start=2):
        try:
            if "label" in fields and rec.get("label"):
                i, j = grid.index_of(rec["label"])
            else:
                i, j = int(rec["row"]) - 1, int(rec["column"]) - 1
                if not (0 <= i < grid.shape[0] and 0 <= j < grid.shape[1]):
                    raise ValueError("row/column outside the grid")
            value = float(rec["deviation_mm"])
        except (ValueError, TypeError, DesignError) as err:
            raise DesignError.single(f"{path}: data line {k}", dict(rec), "a grid point with a numeric deviation_mm",
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
