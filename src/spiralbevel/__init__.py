"""spiralbevel: design, manufacture and contact analysis of spiral bevel gears.

The public API is the curated ``__all__`` below; ``spiralbevel._core`` is private.
"""

from spiralbevel.conventions import Hand, Member, Side
from spiralbevel.errors import DesignError, GeometryError
from spiralbevel.geometry.logspiral import FlankGeometry, LogSpiralFlank

__version__ = "0.1.0"

__all__ = [
    "DesignError",
    "FlankGeometry",
    "GeometryError",
    "Hand",
    "LogSpiralFlank",
    "Member",
    "Side",
]
