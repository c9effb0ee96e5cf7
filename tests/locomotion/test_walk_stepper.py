"""The incremental walker (issue 13; [SH5] §5.1.7, §5.2.4): the next footstep on demand."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.locomotion import footsteps, walk_path
from jackpy.locomotion.stepper import Approach, Balance, Planned, Stepper, constrain_landing
from jackpy.locomotion.walk_gait import START_TIME
from walk_cases import figure_and_params


def test_stepper_fed_a_plan_is_the_planned_walk():
    _, p = figure_and_params("male:50")
    a = np.linspace(0.0, np.pi / 2, 9)
    steps = footsteps.from_path(p, np.column_stack([2.0 - 2.0 * np.cos(a), 2.0 * np.sin(a)]), facing=np.pi / 2)
    ref = walk_path.Walk(steps, p)
    st = Stepper(p, steps[:2], Planned(steps))
    worst, most_ahead = 0.0, 0
    for i in range(int(ref.duration * 12) + 1):
        tg = st.next_frame(0.0 if i == 0 else 1.0 / 12)
        r = ref.at(st.t)
        worst = max(worst, float(np.abs(tg.pelvis - r.pelvis).max()),
                    *(float(np.abs(tg.feet[s] - r.feet[s]).max()) for s in tg.feet))
        # incremental: while footstep j swings in, the stepper knows at most σ_{j+1}
        j = 2 + int(max(0.0, st.t - START_TIME) // p.step_time)
        most_ahead = max(most_ahead, len(st.steps) - 1 - j)
    assert worst == 0.0
    assert most_ahead == 1
    st.next_frame(1.0)
    assert st.steps == steps and st.done


def test_approach_turns_at_most_45_degrees_a_step_and_stands_at_the_target():
    _, p = figure_and_params("male:50")
    target = np.array([-1.5, -1.0])  # behind and to the left of a figure facing +z
    st = Stepper(p, footsteps.standing(p, 0.0, 0.0, 0.0), Approach(target, facing=np.pi))
    steps = st.run()
    turns = [abs((b.psi - a.psi + np.pi) % (2 * np.pi) - np.pi) for a, b in zip(steps[1:], steps[2:])]
    assert max(turns) <= np.radians(45.0) + 1e-9
    assert sum(t > np.radians(44.0) for t in turns) >= 2  # it had to turn round, 45° at a time
    end = 0.5 * (steps[-1].point + steps[-2].point)
    assert np.linalg.norm(end - target) < 0.05
    assert all(abs(np.sin(f.psi)) < 1e-9 and np.cos(f.psi) < 0 for f in steps[-2:])  # facing -z
    walk = walk_path.Walk(steps, p)  # a walk: the feet alternate, it ends standing
    assert walk.duration > 0
    lengths = [np.linalg.norm(b.point - a.point) for a, b in zip(steps[2:], steps[3:])]
    assert max(lengths) <= 1.2 * p.step_length


def test_a_source_giving_the_wrong_foot_is_refused():
    _, p = figure_and_params("female:5")
    stand = footsteps.standing(p, 0.0, 0.0, 0.0)
    st = Stepper(p, stand, lambda s: walk_path.Footstep(0.0, 0.3, 0.0, s.steps[-1].side))
    with pytest.raises(ValueError, match="must be the"):
        st.at(0.0)


def test_constrain_landing_keeps_the_width_and_the_length():
    stance, swing = np.array([0.0, 0.0]), np.array([0.2, 0.0])
    # a landing point across the stance foot is pushed out to the least width beside it
    out = constrain_landing(stance, swing, np.array([-0.1, 0.3]), 0.12, 1.0)
    assert out[0] == pytest.approx(0.12) and out[1] == pytest.approx(0.3)
    # a long step is cut to the longest step, from where the swing foot is
    out = constrain_landing(stance, swing, np.array([0.2, 2.0]), 0.12, 0.6)
    assert np.linalg.norm(out - swing) == pytest.approx(0.6)


def test_balance_source_gives_the_landed_footstep_on_demand():
    """The balance stepper's source through the stepper's next-footstep interface: the swing foot
    (σ_0's side) lands where the decision proposed, by the shared landing rule; the next ask
    without a decision ends the steps; a footsteps-only stepper has no walk."""
    standing = [walk_path.Footstep(0.2, 0.0, 0.3, "right"), walk_path.Footstep(0.0, 0.0, 0.1, "left")]
    source = Balance(0.12, 1.0)
    stepper = Stepper(None, standing, source)
    source.proposed = np.array([-0.1, 0.3])
    f = stepper.next_footstep()
    assert f.side == "right" and f.psi == 0.3
    assert np.allclose(f.point, constrain_landing(standing[1].point, standing[0].point, [-0.1, 0.3], 0.12, 1.0))
    assert f.x == pytest.approx(0.12)  # pushed out to the least width
    assert stepper.next_footstep() is None and stepper.stopped
    with pytest.raises(ValueError, match="footsteps only"):
        stepper.at(0.0)
