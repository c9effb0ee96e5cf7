"""The arm-only reach gives point_reach's answer (arm mode) on the full figure: the same pass/fail
and, out of reach, the same shortfall (it steps by projected BFGS, point_reach by bounded Gauss-Newton:
reached targets end at different points inside the tolerance)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from jackpy.analysis.parts import figure_parts
from jackpy.analysis.reach import Posture, point_reach
from jackpy.population.arm_reach import apply_to_figure, arm_figure, figure_parts_of_arm, reach
from jackpy.population.generate import make_body, make_figure
from jackpy.scene.workplace import load_workplace, resolve_target, stand_figure

SCENE = Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json"


@pytest.mark.parametrize("hand", ["right", "left"])
def test_arm_figure_reach_equals_full_figure_reach(hand: str) -> None:
    wp = load_workplace(SCENE)
    fig = make_figure(make_body(0, "female", {"stature": 1.70}), surfaces=False)
    stand_figure(fig, wp.stand)
    h = figure_parts(fig).hands[hand]
    assert (h.segment, h.site, h.start_joint) == figure_parts_of_arm(hand)
    neutral = Posture.of(fig)
    for ref in ("desk.button", "shelf.box_handle", "panel.switch"):
        p = resolve_target(wp.env, ref)[1]
        full = point_reach(fig, p, hand)
        arm = arm_figure(fig, hand)
        assert np.allclose(arm.site_world(h.segment, h.site), fig.site_world(h.segment, h.site), atol=1e-12)
        mine = reach(arm, p, hand)
        assert mine.reached == full.reached
        if not full.reached:
            assert mine.shortfall == pytest.approx(full.shortfall, abs=1e-4)  # 0.1 mm
        apply_to_figure(arm, fig)  # the reach posture on the full figure puts the hand where the arm's is
        assert np.allclose(fig.site_world(h.segment, h.site), arm.site_world(h.segment, h.site), atol=1e-9)
        neutral.apply(fig)
