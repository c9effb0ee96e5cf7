"""Short steps sideways and backwards (issue 13): the pelvis keeps facing the feet's heading
while the centre site travels straight; the stance feet do not slide."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.locomotion import footsteps, walk_path, walk_solve
from jackpy.locomotion.walk_gait import SIDES
from walk_cases import figure_and_params, sole


@pytest.mark.parametrize("right,forward", [(0.5, 0.0), (0.0, -0.6), (-0.3, -0.3)])
def test_shuffle_keeps_the_heading_and_lands_on_the_goal(right, forward):
    fig, p = figure_and_params("male:50")
    psi = np.radians(30.0)
    steps = footsteps.shuffle(p, 1.0, 2.0, psi, right, forward)
    for a, b in zip(steps, steps[2:]):  # each foot's move
        assert np.linalg.norm(b.point - a.point) <= footsteps.SHUFFLE_STEP * p.step_length + 1e-9
    walk = walk_path.Walk(steps, p)
    assert all(walk.shuffle[2:])
    postures, targets = walk_solve.bake(fig, walk, 8.0)
    prev = None
    for po, tg in zip(postures, targets):
        po.apply_to(fig)
        yaw = float(np.arctan2(tg.pelvis[0, 2], tg.pelvis[2, 2]))
        assert abs(yaw - psi) < 1e-9  # the pelvis faces the feet all along
        s = {side: sole(fig, side) for side in SIDES}
        assert min(v[:, 1].min() for v in s.values()) > -0.002
        if prev is not None:
            for side in SIDES:
                if tg.phase[side] == "flat" and prev[1].phase[side] == "flat":
                    assert np.abs(s[side] - prev[0][side]).max() < 0.002
        prev = (s, tg)
    c = fig.site_world("pelvis", "centre")[:3, 3][[0, 2]]
    lat, fwd = np.array([np.cos(psi), -np.sin(psi)]), np.array([np.sin(psi), np.cos(psi)])
    assert np.linalg.norm(c - (np.array([1.0, 2.0]) - right * lat + forward * fwd)) < 0.05


def test_shuffle_is_for_short_distances():
    _, p = figure_and_params("male:50")
    with pytest.raises(ValueError, match="at most"):
        footsteps.shuffle(p, 0.0, 0.0, 0.0, 0.0, -2.0)


def test_cli_shuffle_and_steer(tmp_path):
    from jackpy.cli import main
    from jackpy.motion import motion_file

    out = tmp_path / "s.motion.json"
    assert main(["walk", "-", "--shuffle", "0.4,0", "--fps", "4", "-o", str(out)]) == 0
    steps = motion_file.load(out).timeline.motions[0].plan["steps"]
    assert all(abs(row[2]) < 1e-12 for row in steps)  # facing +z throughout
    assert np.mean([r[0] for r in steps[-2:]]) == pytest.approx(-0.4)  # to the right of +z is -x
    assert main(["walk", "-", "--to=-1,-1", "--steer", "--fps", "4", "-o", str(out)]) == 0
    steps = motion_file.load(out).timeline.motions[0].plan["steps"]
    turns = [abs((b[2] - a[2] + np.pi) % (2 * np.pi) - np.pi) for a, b in zip(steps[1:], steps[2:])]
    assert max(turns) <= np.radians(45.0) + 1e-9
    assert np.hypot(*(np.mean([r[:2] for r in steps[-2:]], axis=0) - [-1.0, -1.0])) < 0.05
