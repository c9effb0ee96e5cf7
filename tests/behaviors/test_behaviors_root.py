"""Automatic root selection, the 60% and 70% rules with hysteresis (behaviors.md §7 item 8)."""

from jackpy.behaviors.auto_root import select_root

LEG = 0.9
STAND = 0.85


def test_sixty_percent_rule():
    assert select_root("left", 0.65, STAND, LEG) == "right"
    assert select_root("right", 0.35, STAND, LEG) == "left"


def test_hysteresis_band_keeps_the_root():
    root = "right"
    for x in (0.55, 0.45, 0.55, 0.41, 0.59):
        root = select_root(root, x, STAND, LEG)
        assert root == "right"
    assert select_root(root, 0.39, STAND, LEG) == "left"
    assert select_root("left", 0.59, STAND, LEG) == "left"


def test_seated_rule_and_back():
    assert select_root("right", 0.5, 0.69 * LEG, LEG) == "pelvis"
    assert select_root("pelvis", 0.7, 0.72 * LEG, LEG) == "pelvis"
    assert select_root("pelvis", 0.7, 0.8 * LEG, LEG) == "right"
