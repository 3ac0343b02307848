"""Tool paths as CSV: one row per cutter-location point with its tool-axis vector, written atomically.

Format (UTF-8, ``\\n`` line ends)::

    # spiralbevel tool path: 5-axis ball-end, passes along the lengthwise lines of curvature
    # tool_radius_mm = 3
    # scallop_height_mm = 0.01
    # reference = center   (x, y, z is the ball centre; 'tip' = the tool tip on the axis)
    # axis (i, j, k): unit vector from the tool tip toward the spindle; member frame, apex at the origin, axis +z
    path,index,x_mm,y_mm,z_mm,i,j,k
    0,0,...

Numbers are written with ``repr`` (shortest exact float), so a round trip is exact.
"""

from __future__ import annotations

import io
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import DesignError
from .atomic import atomic_write_text

__all__ = ["ToolPathTable", "write_toolpath_csv", "read_toolpath_csv", "COLUMNS"]

COLUMNS = ("path", "index", "x_mm", "y_mm", "z_mm", "i", "j", "k")
_REFERENCES = ("center", "tip")


@dataclass(frozen=True)
class ToolPathTable:
    """Tool path read back from CSV.

    Attributes
    ----------
    path, index : (N,) int
        Pass number and point number within the pass.
    points : (N, 3) float, mm
        Cutter-location points (ball centre or tool tip, see ``reference``).
    axis : (N, 3) float
        Unit tool-axis vectors.
    tool_radius : float, mm
    scallop_height : float or None, mm
    reference : str
        ``"center"`` or ``"tip"``.
    """

    path: np.ndarray
    index: np.ndarray
    points: np.ndarray
    axis: np.ndarray
    tool_radius: float
    scallop_height: "float | None"
    reference: str


def format_toolpath_csv(toolpath, reference: str = "center") -> str:
    """CSV text of a :class:`~spiralbevel.manufacturing.toolpath.ToolPath` (see the module docstring).

    Parameters
    ----------
    toolpath : ToolPath
    reference : {"center", "tip"}
        Which point goes into x, y, z: the ball centre (default) or the tool tip.

    Returns
    -------
    str
    """
    if reference not in _REFERENCES:
        raise DesignError.single("reference", reference, " or ".join(_REFERENCES), "-")
    pts = np.asarray(toolpath.stacked(reference), float).tolist()  # Python floats: repr is the shortest exact
    axis = np.asarray(toolpath.stacked("axis"), float).tolist()
    pidx, iidx = toolpath.path_index.tolist(), toolpath.point_index.tolist()
    out = io.StringIO()
    out.write("# spiralbevel tool path: 5-axis ball-end, passes along the lengthwise lines of curvature\n")
    out.write(f"# tool_radius_mm = {float(toolpath.tool_radius)!r}\n")
    out.write(f"# scallop_height_mm = {float(toolpath.scallop_height)!r}\n")
    where = "ball centre" if reference == "center" else "tool tip on the axis"
    out.write(f"# reference = {reference}   (x, y, z is the {where})\n")
    out.write("# axis (i, j, k): unit vector from the tool tip toward the spindle; member frame, apex at the origin, "
              "axis +z\n")
    out.write(",".join(COLUMNS) + "\n")
    for n in range(len(pidx)):
        p, a = pts[n], axis[n]
        out.write(f"{pidx[n]},{iidx[n]},{p[0]!r},{p[1]!r},{p[2]!r},{a[0]!r},{a[1]!r},{a[2]!r}\n")
    return out.getvalue()


def write_toolpath_csv(path: "str | os.PathLike[str]", toolpath, reference: str = "center") -> Path:
    """Write a tool path as CSV, atomically (whole file or nothing).

    Parameters
    ----------
    path : str or PathLike
        Output file; its directory must exist.
    toolpath : ToolPath
        From :func:`spiralbevel.manufacturing.toolpath.plan_toolpath`.
    reference : {"center", "tip"}
        Point written as x_mm, y_mm, z_mm.

    Returns
    -------
    pathlib.Path
    """
    return atomic_write_text(path, format_toolpath_csv(toolpath, reference))


def read_toolpath_csv(path: "str | os.PathLike[str]") -> ToolPathTable:
    """Read a CSV written by :func:`write_toolpath_csv`.

    Parameters
    ----------
    path : str or PathLike

    Returns
    -------
    ToolPathTable

    Raises
    ------
    DesignError
        Missing tool radius, wrong header or malformed rows (the message names the file and line).
    """
    meta = {}
    header = None
    rows = []
    text = Path(path).read_text(encoding="utf-8")
    for lineno, line in enumerate(text.splitlines(), 1):
        if not line.strip():
            continue
        if line.startswith("#"):
            body = line[1:].split("(")[0]
            if "=" in body:
                key, val = body.split("=", 1)
                meta[key.strip()] = val.strip()
            continue
        if header is None:
            header = tuple(c.strip() for c in line.split(","))
            if header != COLUMNS:
                raise DesignError.single(f"{path}:{lineno}", line, ",".join(COLUMNS), "-", "unexpected CSV header")
            continue
        parts = line.split(",")
        try:
            if len(parts) != len(COLUMNS):
                raise ValueError
            rows.append((int(parts[0]), int(parts[1]), *map(float, parts[2:])))
        except ValueError:
            raise DesignError.single(f"{path}:{lineno}", line, "path,index and six numbers", "-",
                                     "malformed tool-path row") from None
    if header is None:
        raise DesignError.single(str(path), "no header", ",".join(COLUMNS), "-", "not a tool-path CSV")
    try:
        radius = float(meta["tool_radius_mm"])
    except (KeyError, ValueError):
        raise DesignError.single(f"{path}: tool_radius_mm", meta.get("tool_radius_mm"), "a number in the header",
                                 "mm") from None
    scallop = float(meta["scallop_height_mm"]) if "scallop_height_mm" in meta else None
    reference = meta.get("reference", "center")
    arr = np.array(rows, dtype=float).reshape(-1, 8)
    return ToolPathTable(path=arr[:, 0].astype(int), index=arr[:, 1].astype(int), points=arr[:, 2:5],
                         axis=arr[:, 5:8], tool_radius=radius, scallop_height=scallop, reference=reference)
