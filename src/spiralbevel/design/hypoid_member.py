"""One member's view of an ISO 23509 hypoid blank.

A hypoid pair has two mean cone distances (R_m1 of the pinion, R_m2 of the wheel, ISO 23509 Method 1); the flank
generation, the basic settings and the mean point of a member read the blank's single ``Rm``. :func:`member_blank`
gives each member its own: the pinion sees R_m1, the wheel R_m2 (which is also the blank's ``Rm``). Every other
attribute is the blank's own (per-member names such as ``delta1``, ``ham2``, ``Re1`` already carry the index). For a
spiral bevel blank (R_m1 = R_m2) the view changes nothing.
"""

from __future__ import annotations

from spiralbevel.conventions import Member

__all__ = ["member_blank"]


class _MemberBlank:
    """Attribute view of a blank with ``Rm`` replaced by the member's mean cone distance."""

    def __init__(self, blank, member: Member):
        self._blank, self.member = blank, Member(member)
        i = self.member.index
        self.Rm = float(getattr(blank, f"Rm{i}", blank.Rm))

    def __getattr__(self, name):
        return getattr(self._blank, name)

    def __repr__(self) -> str:
        return f"member_blank({self.member.value}, Rm={self.Rm:.4f} mm)"


def member_blank(blank, member):
    """The blank as seen by one member: ``Rm`` = R_m1 for the pinion, R_m2 for the wheel (mm), all else unchanged.

    Parameters
    ----------
    blank : BevelBlank
        ISO 23509 blank, Method 0 or Method 1.
    member : Member

    Returns
    -------
    object
        Read-only attribute view of ``blank``.
    """
    return _MemberBlank(blank, member)
