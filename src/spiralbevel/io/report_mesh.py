"""Triangle meshes of the meshing pair for the 3-D view of ``report.html``.

One tooth per member (the job's tooth mesh, welded and, past a triangle budget, decimated by vertex clustering) and
the placement of each member in the pair frame; the viewer draws the tooth z times about the member axis.

Pair frame (as in the job's TCA): the pinion frame, apex at the origin, pinion axis +z. The gear axis is
``(-sin Sigma, 0, cos Sigma)``; both members are turned about their axes so that the pitch point of the mean cone
distance lies in the plane y = 0 at x < 0, where the centre of a pinion tooth meets the centre of a gear tooth space.
Rolling: a pinion turn ``phi`` about its axis goes with a gear turn ``-phi z1 / z2`` about the gear axis (equal pitch
velocities at the pitch point).
"""

from __future__ import annotations

import base64
import math
from dataclasses import dataclass

import numpy as np

__all__ = ["ViewMesh", "weld", "decimate", "tooth_centre_angle", "pair_placements", "view_payload"]

#: triangles per tooth above which the view mesh is decimated (the viewer draws z1 + z2 copies of the teeth)
MAX_TOOTH_TRIANGLES = 6000


@dataclass(frozen=True)
class ViewMesh:
    """Indexed triangle mesh of one tooth, member frame.

    Attributes
    ----------
    vertices : (n, 3) float32, mm
    normals : (n, 3) float32
        Unit vertex normals (area-weighted mean of the face normals).
    faces : (m, 3) int
        Vertex indices, counter-clockwise seen from outside.
    """

    vertices: np.ndarray
    normals: np.ndarray
    faces: np.ndarray


def _vertex_normals(v: np.ndarray, f: np.ndarray) -> np.ndarray:
    fn = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])  # length = 2 * area: area-weighted sum
    n = np.zeros_like(v)
    for k in range(3):
        np.add.at(n, f[:, k], fn)
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return n / np.where(length > 0.0, length, 1.0)


def _clean(v: np.ndarray, f: np.ndarray) -> ViewMesh:
    f = f[(f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])]
    used, f = np.unique(f, return_inverse=True)
    v = v[used]
    f = f.reshape(-1, 3)
    return ViewMesh(v.astype(np.float32), _vertex_normals(v, f).astype(np.float32), f)


def weld(triangles: np.ndarray, tol: float = 1e-4) -> ViewMesh:
    """Indexed mesh from a triangle soup (as read from STL).

    Parameters
    ----------
    triangles : (m, 3, 3) float, mm
        Corner points of each triangle.
    tol : float, mm
        Corners closer than about ``tol`` become one vertex.
    """
    p = np.asarray(triangles, dtype=float).reshape(-1, 3)
    key = np.round(p / tol).astype(np.int64)
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    return _clean(p[first], inverse.reshape(-1, 3))


def decimate(mesh: ViewMesh, max_triangles: int = MAX_TOOTH_TRIANGLES) -> ViewMesh:
    """Vertex clustering: merge the vertices of each cell of a grid, cells grown until at most ``max_triangles`` stay.

    Cells are boxes aligned with the mesh's bounding box; each cell's vertices move to their mean. A view mesh only:
    the result may have small holes where a cell spans both flanks of a thin top land.
    """
    if len(mesh.faces) <= max_triangles:
        return mesh
    v = mesh.vertices.astype(float)
    lo, span = v.min(0), np.ptp(v, 0).max()
    cells = 256
    while cells > 2:
        key = np.floor((v - lo) / (span / cells)).astype(np.int64)
        _, inverse = np.unique(key, axis=0, return_inverse=True)
        f = inverse.reshape(-1)[mesh.faces]
        keep = (f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])
        if keep.sum() <= max_triangles:
            inverse = inverse.reshape(-1)
            centre = np.zeros((inverse.max() + 1, 3))
            np.add.at(centre, inverse, v)
            centre /= np.bincount(inverse)[:, None]
            return _clean(centre, f[keep])
        cells = int(cells * 0.8)
    return mesh


def tooth_centre_angle(vertices: np.ndarray) -> float:
    """Angle about +z, rad, of a tooth's centre on the sphere of its middle cone distance.

    The circular mean of the azimuths of the vertices whose distance from the apex lies within 1 % of the middle of
    their range (toe to heel); the two flanks contribute alike, so the mean is the tooth's centre line there.
    """
    v = np.asarray(vertices, dtype=float)
    r = np.linalg.norm(v, axis=1)
    mid = 0.5 * (r.min() + r.max())
    band = np.abs(r - mid) <= 0.01 * mid
    if band.sum() < 3:
        band = np.ones(len(v), bool)
    a = np.arctan2(v[band, 1], v[band, 0])
    return float(np.arctan2(np.sin(a).mean(), np.cos(a).mean()))


def _rot_z(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _rot_y(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def pair_placements(shaft_angle: float, teeth: tuple[int, int], centres: tuple[float, float]):
    """Rotations (3, 3) from the member frames of pinion and gear to the pair frame (see the module notes).

    Parameters
    ----------
    shaft_angle : float, rad
        Sigma, the angle between the member axes.
    teeth : (int, int)
        z1, z2.
    centres : (float, float), rad
        :func:`tooth_centre_angle` of the pinion tooth and of the gear tooth, member frames.

    Returns
    -------
    (3, 3) float, (3, 3) float
        Pinion: tooth centre turned to the azimuth pi. Gear: the centre of the space after its tooth turned to the
        azimuth 0 of its frame, then the frame turned by -Sigma about y (gear axis to ``(-sin Sigma, 0, cos Sigma)``,
        azimuth 0 onto the pitch point at x < 0).
    """
    z2 = teeth[1]
    pinion = _rot_z(math.pi - centres[0])
    gear = _rot_y(-shaft_angle) @ _rot_z(-centres[1] - math.pi / z2)
    return pinion, gear


def _b64(a: np.ndarray) -> str:
    return base64.b64encode(np.ascontiguousarray(a).tobytes()).decode("ascii")


def view_payload(meshes: dict, teeth: dict, shaft_angle: float) -> dict:
    """JSON-ready data of the 3-D view.

    Parameters
    ----------
    meshes : {"pinion": ViewMesh, "gear": ViewMesh}
        One tooth of each member, member frame.
    teeth : {"pinion": int, "gear": int}
    shaft_angle : float, rad

    Returns
    -------
    dict
        ``members``: per member the name, z, a row-major 3x3 placement, the rolling ratio (turn per pinion turn),
        base64 little-endian float32 ``positions`` and int8 ``normals`` (x 127), and uint16 or uint32 ``indices``.
    """
    z = (int(teeth["pinion"]), int(teeth["gear"]))
    centres = (tooth_centre_angle(meshes["pinion"].vertices), tooth_centre_angle(meshes["gear"].vertices))
    placement = dict(zip(("pinion", "gear"), pair_placements(shaft_angle, z, centres)))
    members = []
    for name, ratio in (("pinion", 1.0), ("gear", -z[0] / z[1])):
        m = meshes[name]
        index_type = np.uint16 if len(m.vertices) < 65536 else np.uint32
        members.append({
            "name": name, "teeth": int(teeth[name]), "placement": placement[name].reshape(-1).tolist(),
            "ratio": ratio, "positions": _b64(m.vertices.astype("<f4")),
            "normals": _b64(np.clip(np.round(m.normals * 127.0), -127, 127).astype(np.int8)),
            "indices": _b64(m.faces.astype(index_type).astype(np.dtype(index_type).newbyteorder("<"))),
            "index_bits": 16 if index_type is np.uint16 else 32, "triangles": int(len(m.faces)),
        })
    return {"members": members, "shaft_angle_deg": math.degrees(shaft_angle)}
