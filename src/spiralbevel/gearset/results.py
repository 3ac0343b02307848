"""Result objects of :class:`~spiralbevel.gearset.GearSet`: compute -> result -> ``.plot()``.

Each holds the report.json section the main job writes for the same analysis (built by the same function) and the
library's own result object. ``to_dict()`` is that section as plain JSON values; attributes give the headline figures
in the units of the report: mm, degrees, arcsec for transmission errors, N/mm^2, N m.
"""

from __future__ import annotations

import html
import math

import numpy as np

from ..errors import NoContactError

__all__ = ["TCA", "LTCA", "EaseOff", "Sensitivity", "MachineSummary", "MeasurementGrids", "Rating", "html_table"]


def html_table(title: str, rows: dict) -> str:
    """A small HTML table of scalar rows for ``_repr_html_`` (numbers to 6 significant digits)."""
    def cell(v):
        if isinstance(v, float):
            return f"{v:.6g}"
        return html.escape(str(v))

    body = "".join(f"<tr><th style='text-align:left'>{html.escape(str(k))}</th><td>{cell(v)}</td></tr>"
                   for k, v in rows.items())
    return f"<table><caption style='text-align:left'><b>{html.escape(title)}</b></caption>{body}</table>"


def _scalars(d: dict) -> dict:
    """The scalar (number, string, bool) entries of a section, for reprs."""
    return {k: v for k, v in d.items() if isinstance(v, (int, float, str, bool)) and not isinstance(v, np.ndarray)}


class _Result:
    """Common part: the report.json section, ``to_dict``, ``repr``, ``_repr_html_``."""

    _name = "result"

    def __init__(self, section: dict):
        self._section = section

    def to_dict(self) -> dict:
        """The report.json section of this analysis (plain JSON values: lists, floats, None for NaN)."""
        from ..io.report import to_jsonable

        return to_jsonable(self._section)

    def _headline(self) -> dict:
        return _scalars(self.to_dict())

    def __repr__(self) -> str:
        items = ", ".join(f"{k}={v + 0.0:.6g}" if isinstance(v, float) else f"{k}={v!r}"
                          for k, v in self._headline().items())
        return f"{type(self).__name__}({items})"

    def _repr_html_(self) -> str:
        return html_table(self._name, self._headline())


class TCA(_Result):
    """Tooth contact analysis of one side over one mesh cycle.

    Attributes
    ----------
    side : str
    result : TCAResult or None
        The solver's result (internal units: rad, mm); None when too few positions had contact.
    """

    _name = "Tooth contact analysis"

    def __init__(self, side, result, section, outline):
        super().__init__(section)
        self.side, self.result, self._outline = side, result, outline

    @property
    def ok(self) -> bool:
        """True when a transmission-error curve was found (no ``error`` in the section)."""
        return "error" not in self._section

    def _get(self, key):
        if key not in self._section:
            raise NoContactError(f"TCA {self.side} side: {self._section.get('error', 'no ' + key)}")
        return self._section[key]

    @property
    def peak_to_peak_arcsec(self) -> float:
        """Peak-to-peak transmission error of the contact envelope, arcsec."""
        return float(self._get("peak_to_peak_arcsec"))

    @property
    def max_transmission_error_arcsec(self) -> float:
        return float(self._get("max_transmission_error_arcsec"))

    @property
    def min_transmission_error_arcsec(self) -> float:
        return float(self._get("min_transmission_error_arcsec"))

    @property
    def pinion_rotation_deg(self) -> np.ndarray:
        """(n,) float, deg: pinion rotations of the positions with contact (from the mean position)."""
        key = "pinion_rotation_deg" if "pinion_rotation_deg" in self._section else "pinion_rotation_rad"
        v = np.asarray(self._get(key), float)
        return v if key.endswith("_deg") else np.degrees(v)

    @property
    def transmission_error_arcsec(self) -> np.ndarray:
        """(n,) float, arcsec: transmission error at those positions."""
        return np.asarray(self._get("transmission_error_arcsec"), float)

    def _headline(self):
        d = self.to_dict()
        keys = ("status", "positions", "contact_positions", "peak_to_peak_arcsec", "max_transmission_error_arcsec",
                "min_transmission_error_arcsec", "semi_major_axis_mean_mm", "max_abs_transmission_error_arcsec",
                "line_contact_positions", "error")
        return {"side": self.side, **{k: d[k] for k in keys if k in d}}

    def plot(self):
        """TE curves, contact path on the projected flanks and contact ellipses. Returns a matplotlib Figure."""
        if self.result is None:
            raise NoContactError(f"TCA {self.side} side: nothing to plot ({self._section.get('error')})")
        o = self._outline or (None, None)
        fig = self.result.plot(outline1=o[0], outline2=o[1])
        fig.suptitle(f"TCA, {self.side} side")
        return fig


class LTCA(_Result):
    """Loaded tooth contact analysis over one mesh cycle (``result``: :class:`~spiralbevel.meshing.ltca.LTCAResult`,
    None when a position had no contact of the real flanks)."""

    _name = "Loaded tooth contact analysis"

    def __init__(self, side, result, section):
        super().__init__(section)
        self.side, self.result = side, result

    def _headline(self):
        d = self.to_dict()
        return {k: v for k, v in _scalars(d).items()}

    def plot(self):
        """Transmission errors, load sharing and the contact pressure. Returns a matplotlib Figure."""
        if self.result is None:
            raise NoContactError(f"LTCA {self.side} side: nothing to plot ({self._section.get('error')})")
        fig = self.result.plot()
        fig.suptitle(f"Loaded TCA, {self.side} side")
        return fig


class EaseOff(_Result):
    """Ease-off of the drive and coast pinion flanks (``maps``: {side: :class:`~spiralbevel.meshing.easeoff.EaseOff`
    or None}). Positive = clearance (material removed from the pinion), mm."""

    _name = "Ease-off"

    def __init__(self, section, maps):
        super().__init__(section)
        self.maps = maps

    def _headline(self):
        d = self.to_dict()
        return {f"{side} {k}": v for side, sec in d.items() if isinstance(sec, dict)
                for k, v in _scalars(sec).items()}

    def plot(self, side: str = "drive", kind: str = "surface"):
        """The ease-off map of one side (um). Returns a matplotlib Figure."""
        eo = self.maps.get(side)
        if eo is None:
            raise NoContactError(f"ease-off {side} side: {self._section.get(side, {}).get('error', 'not computed')}")
        return eo.plot(kind=kind, title=f"Ease-off, {side} side (+ = clearance)")


class Sensitivity(_Result):
    """TE level and contact-pattern shift of one side under each small misalignment of the main job's study."""

    _name = "Misalignment sensitivity"

    def cases(self) -> list[str]:
        """Names of the misalignment cases."""
        return [k for k, v in self._section.items() if isinstance(v, dict) and k != "aligned"]

    def _headline(self):
        d = self.to_dict()
        out = {"side": d.get("side")}
        for name in self.cases():
            c = d[name]
            if "peak_to_peak_arcsec" in c:
                out[f"{name} TE p-p_arcsec"] = c["peak_to_peak_arcsec"]
        return out

    def plot(self):
        """Bar charts: TE peak-to-peak and contact shift (along face, along profile) per case. Returns a Figure."""
        import matplotlib.pyplot as plt

        d = self.to_dict()
        names = [n for n in self.cases() if "contact_shift_along_face_mm" in d[n]]
        fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
        x = np.arange(len(names))
        a1.bar(x, [d[n]["peak_to_peak_arcsec"] or 0.0 for n in names])
        if isinstance(d.get("aligned"), dict) and d["aligned"].get("peak_to_peak_arcsec") is not None:
            a1.axhline(d["aligned"]["peak_to_peak_arcsec"], color="k", ls="--", label="aligned")
            a1.legend()
        a1.set_xticks(x, names)
        a1.set_ylabel("TE peak-to-peak, arcsec")
        w = 0.38
        a2.bar(x - w / 2, [d[n]["contact_shift_along_face_mm"] for n in names], w, label="along face (heel +)")
        a2.bar(x + w / 2, [d[n]["contact_shift_along_profile_mm"] for n in names], w, label="along profile (top +)")
        a2.set_xticks(x, names)
        a2.set_ylabel("contact shift at the mean position, mm")
        a2.legend()
        fig.suptitle(f"Misalignment sensitivity, {d.get('side')} side")
        return fig


class MachineSummary(_Result):
    """Cutters, machine settings and achieved flank data of the four flanks (report.json ``flanks`` and
    ``machine_settings``)."""

    _name = "Machine summary"

    def __init__(self, flanks, machines):
        super().__init__({"flanks": flanks, "machine_settings": machines})

    def _headline(self):
        d = self.to_dict()["flanks"]
        return {f"{m} {s}": f"spiral {v['spiral_angle_deg']:.4f} deg, pressure {v['pressure_angle_deg']:.4f} deg"
                for m, sides in d.items() for s, v in sides.items()}

    def rows(self, member, side) -> list:
        """(name, value, unit) rows of the machine summary of one flank."""
        from ..conventions import Member, Side

        return self._section["machine_settings"][Member(member).value][Side(side).value]["summary"]

    def plot(self):
        """The four machine summaries as tables. Returns a matplotlib Figure."""
        import matplotlib.pyplot as plt

        ms = self._section["machine_settings"]
        flanks = [(m, s) for m in ("pinion", "gear") for s in ("convex", "concave") if s in ms.get(m, {})]
        fig, axes = plt.subplots(1, len(flanks), figsize=(4.2 * len(flanks), 6), layout="constrained")
        for ax, (m, s) in zip(np.atleast_1d(axes), flanks):
            rows = [[str(c) for c in r] for r in ms[m][s]["summary"]]
            ax.axis("off")
            ax.set_title(f"{m} {s}")
            if rows:
                t = ax.table(cellText=rows, loc="upper center", cellLoc="left")
                t.auto_set_font_size(False)
                t.set_fontsize(7)
        return fig


class MeasurementGrids(_Result):
    """Nominal CMM grids (points, outward normals, mm) of the four flanks: {(member, side): MeasurementGrid}."""

    _name = "Measurement grids"

    def __init__(self, grids):
        self.grids = grids
        section = {"grid": [9, 5], "deviation_sign": "positive = material added"}
        for (m, s), g in grids.items():
            section[f"{m.value}_{s.value}"] = {"points_mm": g.points, "normals": g.normals}
        super().__init__(section)

    def _headline(self):
        return {"flanks": len(self.grids), "grid": "9 x 5", "deviation_sign": "positive = material added"}

    def plot(self):
        """The grids in the axial section (axial position against radius). Returns a matplotlib Figure."""
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(7, 5), layout="constrained")
        for (m, s), g in self.grids.items():
            p = np.asarray(g.points).reshape(-1, 3)
            ax.plot(p[:, 2], np.hypot(p[:, 0], p[:, 1]), "o", ms=3, label=f"{m.value} {s.value}")
        ax.set_xlabel("axial position, mm")
        ax.set_ylabel("radius, mm")
        ax.set_aspect("equal")
        ax.legend()
        ax.set_title("Nominal measurement grids (axial section)")
        return fig


class Rating(_Result):
    """ISO 10300 Method B1 load capacity (``result``: :class:`~spiralbevel.rating.RatingResult`)."""

    _name = "Load capacity (ISO 10300 B1)"

    def __init__(self, result, section):
        super().__init__(section)
        self.result = result

    def _headline(self):
        d = self.to_dict()
        keys = [k for k in d if k.startswith("S_") or k.startswith("safety")]
        return {k: d[k] for k in keys if isinstance(d[k], (int, float))} or _scalars(d)

    def plot(self):
        """Safety factors against their minima. Returns a matplotlib Figure."""
        import matplotlib.pyplot as plt

        h = {k: v for k, v in self._headline().items() if isinstance(v, (int, float)) and math.isfinite(v)}
        fig, ax = plt.subplots(figsize=(6, 3.5), layout="constrained")
        ax.bar(list(h), list(h.values()))
        ax.axhline(1.0, color="k", lw=0.8)
        ax.set_ylabel("-")
        ax.set_title("ISO 10300 B1 safety factors")
        return fig
