from spiralbevel.conventions import Hand, Member, Side


def test_member_indices():
    assert Member.PINION.index == 1 and Member.GEAR.index == 2


def test_hand_signs_and_opposite():
    assert Hand.RIGHT.sign == 1 and Hand.LEFT.sign == -1
    assert Hand.RIGHT.opposite is Hand.LEFT and Hand("LH") is Hand.LEFT


def test_sides_mate():
    # pinion concave meshes with gear convex (docs/conventions.md)
    assert Side.CONCAVE.mate is Side.CONVEX and Side.CONVEX.mate is Side.CONCAVE
