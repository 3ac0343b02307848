"""STL export of triangle meshes (binary and ASCII), written atomically, and a reader for round trips.

Binary STL: an 80-byte header, a little-endian uint32 face count, then per face 12 float32 (normal, three corners)
and a uint16 attribute count. ASCII STL: ``solid name`` / ``facet normal`` / ``outer loop`` / ``vertex`` ... /
``endsolid name``. Coordinates are written in mm (STL carries no unit; mm is the convention of slicers and CAD).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np

from spiralbevel.errors import DesignError
from spiralbevel.geometry.surface_mesh import TriangleMesh
from spiralbevel.io.atomic import atomic_write_bytes

__all__ = ["write_stl", "read_stl", "stl_bytes"]

_RECORD = np.dtype([("normal", "<f4", (3,)), ("corners", "<f4", (3, 3)), ("attr", "<u2")])


def _check_mesh(mesh) -> TriangleMesh:
    if not isinstance(mesh, TriangleMesh):
        raise DesignError.single("mesh", type(mesh).__name__, "a TriangleMesh", "-")
    if len(mesh.faces) == 0:
        raise DesignError.single("mesh.faces", 0, "at least one face", "-")
    if not np.all(np.isfinite(mesh.vertices)):
        raise DesignError.single("mesh.vertices", "non-finite values", "finite coordinates", "mm")
    if mesh.faces.min() < 0 or mesh.faces.max() >= len(mesh.vertices):
        raise DesignError.single("mesh.faces", "index out of range", f"0 <= index < {len(mesh.vertices)}", "-")
    return mesh


def _check_name(name: str) -> str:
    if not isinstance(name, str) or not re.fullmatch(r"[\x21-\x7e]([\x20-\x7e]*[\x21-\x7e])?", name) or len(name) > 79:
        raise DesignError.single("name", name, "1 to 79 printable ASCII characters, no leading/trailing space", "-")
    return name


def stl_bytes(mesh: TriangleMesh, binary: bool = True, name: str = "spiralbevel") -> bytes:
    """The STL file content of ``mesh`` (see :func:`write_stl`)."""
    mesh = _check_mesh(mesh)
    name = _check_name(name)
    tri = mesh.triangles
    normals = mesh.face_normals(unit=True)
    if binary:
        header = name.encode("ascii")[:80].ljust(80, b" ")
        if header.startswith(b"solid"):  # a binary header must not look like an ASCII file
            header = (b"binary " + header)[:80]
        rec = np.zeros(len(tri), dtype=_RECORD)
        rec["normal"] = normals
        rec["corners"] = tri
        return header + np.uint32(len(tri)).tobytes() + rec.tobytes()
    lines = [f"solid {name}"]
    for n, t in zip(normals, tri):
        lines.append("  facet normal {:.9e} {:.9e} {:.9e}".format(*n))
        lines.append("    outer loop")
        lines.extend("      vertex {:.9e} {:.9e} {:.9e}".format(*v) for v in t)
        lines.append("    endloop")
        lines.append("  endfacet")
    lines.append(f"endsolid {name}")
    return ("\n".join(lines) + "\n").encode("ascii")


def write_stl(path: "str | os.PathLike[str]", mesh: TriangleMesh, binary: bool = True,
              name: str = "spiralbevel") -> Path:
    """Write a triangle mesh as an STL file, atomically.

    Parameters
    ----------
    path : str or PathLike
        Target file; its directory must exist. The file is written to a temporary sibling and moved into place.
    mesh : TriangleMesh
        Mesh in mm; facet normals are computed from the (outward) face orientation.
    binary : bool
        Binary STL (float32 coordinates, compact) when True, ASCII STL (9 significant digits) otherwise.
    name : str
        Solid name (ASCII) or, for binary files, the 80-byte header text.

    Returns
    -------
    pathlib.Path
        The written path.
    """
    return atomic_write_bytes(path, stl_bytes(mesh, binary=binary, name=name))


def read_stl(path: "str | os.PathLike[str]") -> TriangleMesh:
    """Read a binary or ASCII STL file into an (unwelded) TriangleMesh: three vertices per face, in file order.

    Parameters
    ----------
    path : str or PathLike
        STL file.

    Returns
    -------
    TriangleMesh
        ``vertices (3m, 3)`` float64 (float32 values for binary files) and ``faces = arange(3m).reshape(m, 3)``.
    """
    data = Path(path).read_bytes()
    if len(data) >= 84:
        count = int(np.frombuffer(data, "<u4", 1, 80)[0])
        if len(data) == 84 + count * _RECORD.itemsize:
            rec = np.frombuffer(data, _RECORD, count, 84)
            corners = rec["corners"].astype(float).reshape(-1, 3)
            return TriangleMesh(corners, np.arange(len(corners)).reshape(-1, 3))
    text = data.decode("ascii", errors="strict")
    if not text.lstrip().startswith("solid"):
        raise DesignError.single("path", str(path), "a binary or ASCII STL file", "-", "unrecognised content")
    values = re.findall(r"vertex\s+(\S+)\s+(\S+)\s+(\S+)", text)
    corners = np.array(values, dtype=float).reshape(-1, 3)
    if len(corners) % 3:
        raise DesignError.single("path", str(path), "3 vertices per facet", "-", "truncated ASCII STL")
    return TriangleMesh(corners, np.arange(len(corners)).reshape(-1, 3))
