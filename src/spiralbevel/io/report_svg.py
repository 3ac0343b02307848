"""Inline SVG line charts for ``report.html`` (no plotting library: the page must stand alone)."""

from __future__ import annotations

import math
from html import escape

__all__ = ["line_chart", "nice_ticks"]

_COLOURS = ("#1f5fa8", "#c8541e", "#2e8b57", "#7b3fa0", "#a0522d", "#444444")


def nice_ticks(lo: float, hi: float, n: int = 6) -> list[float]:
    """About ``n`` round tick values covering [lo, hi] (steps 1, 2 or 5 times a power of ten)."""
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return []
    if hi - lo <= 1e-12 * max(1.0, abs(lo), abs(hi)):
        lo, hi = lo - 0.5, hi + 0.5
    raw = (hi - lo) / max(n - 1, 1)
    mag = 10.0 ** math.floor(math.log10(raw))
    step = next(m * mag for m in (1.0, 2.0, 5.0, 10.0) if m * mag >= raw)
    first = math.floor(lo / step) * step
    ticks, t = [], first
    while t <= hi + 0.5 * step:
        ticks.append(round(t, 12))
        t += step
    return ticks


def _fmt(v: float) -> str:
    return f"{v:.6g}"


def line_chart(series: list[tuple[str, list, list]], xlabel: str, ylabel: str, title: str,
               width: int = 640, height: int = 300) -> str:
    """SVG of one or more polylines with axes, ticks, a legend and a tooltip per point.

    Parameters
    ----------
    series : list of (label, x, y)
        ``y`` may hold ``None`` (no value at that ``x``): the line breaks there.
    xlabel, ylabel, title : str
    """
    pts = [(x, y) for _, xs, ys in series for x, y in zip(xs, ys) if x is not None and y is not None]
    if not pts:
        return f'<p class="note">{escape(title)}: no values to plot.</p>'
    xt = nice_ticks(min(p[0] for p in pts), max(p[0] for p in pts))
    yt = nice_ticks(min(p[1] for p in pts), max(p[1] for p in pts))
    x0, x1, y0, y1 = xt[0], xt[-1], yt[0], yt[-1]
    # legend below the x-axis label, in rows (never over the curves)
    rows: list[list[tuple[int, str, float]]] = [[]]
    x_at = 64.0
    for i, (label, _, _) in enumerate(series):
        w = 34 + 6.2 * len(label)
        if rows[-1] and x_at + w > width - 16:
            rows.append([])
            x_at = 64.0
        rows[-1].append((i, label, x_at))
        x_at += w
    left, right, top, bottom = 64, 16, 28, 44 + 16 * len(rows)
    height += 16 * len(rows)
    pw, ph = width - left - right, height - top - bottom

    def sx(x):
        return left + (x - x0) / (x1 - x0) * pw

    def sy(y):
        return top + (y1 - y) / (y1 - y0) * ph

    out = [f'<svg class="chart" viewBox="0 0 {width} {height}" width="{width}" height="{height}" role="img" '
           f'aria-label="{escape(title)}" xmlns="http://www.w3.org/2000/svg">',
           f'<text x="{left + pw / 2}" y="16" text-anchor="middle" class="ct">{escape(title)}</text>']
    for t in xt:
        out.append(f'<line x1="{sx(t):.1f}" y1="{top}" x2="{sx(t):.1f}" y2="{top + ph}" class="grid"/>'
                   f'<text x="{sx(t):.1f}" y="{top + ph + 14}" text-anchor="middle">{_fmt(t)}</text>')
    for t in yt:
        out.append(f'<line x1="{left}" y1="{sy(t):.1f}" x2="{left + pw}" y2="{sy(t):.1f}" class="grid"/>'
                   f'<text x="{left - 5}" y="{sy(t) + 4:.1f}" text-anchor="end">{_fmt(t)}</text>')
    out.append(f'<rect x="{left}" y="{top}" width="{pw}" height="{ph}" class="frame"/>')
    out.append(f'<text x="{left + pw / 2}" y="{top + ph + 32}" text-anchor="middle">{escape(xlabel)}</text>')
    out.append(f'<text transform="translate(14 {top + ph / 2}) rotate(-90)" text-anchor="middle">{escape(ylabel)}'
               '</text>')
    for i, (label, xs, ys) in enumerate(series):
        colour = _COLOURS[i % len(_COLOURS)]
        runs: list[list[tuple[float, float]]] = []
        run: list[tuple[float, float]] = []
        for x, y in zip(xs, ys):
            if x is None or y is None:
                if run:
                    runs.append(run)
                run = []
            else:
                run.append((x, y))
        runs.append(run)
        for r in runs:
            if len(r) > 1:
                d = " ".join(f"{sx(x):.1f},{sy(y):.1f}" for x, y in r)
                out.append(f'<polyline points="{d}" fill="none" stroke="{colour}" stroke-width="1.6"/>')
            for x, y in r:
                out.append(f'<circle cx="{sx(x):.1f}" cy="{sy(y):.1f}" r="2.2" fill="{colour}"><title>'
                           f'{escape(label)}: {_fmt(x)}, {_fmt(y)}</title></circle>')
    for k, row in enumerate(rows):
        ly = top + ph + 50 + 16 * k
        for i, label, lx in row:
            colour = _COLOURS[i % len(_COLOURS)]
            out.append(f'<line x1="{lx:.0f}" y1="{ly - 4}" x2="{lx + 18:.0f}" y2="{ly - 4}" stroke="{colour}" '
                       f'stroke-width="2"/><text x="{lx + 22:.0f}" y="{ly}">{escape(label)}</text>')
    out.append("</svg>")
    return "".join(out)
