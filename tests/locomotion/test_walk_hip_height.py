"""The hip-height rule of curved-path walking ([SH5] §5.2.3, eq. 5.14; issue 13): the stance leg
keeps the length ω(t) it has at that moment in the underlying 1-D walk."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.locomotion import footsteps, walk_path
from jackpy.locomotion.walk_gait import DOUBLE_SUPPORT, MAX_LEG
from tests.locomotion.walk_cases import S_END_HEADING, baked, figure_and_params


def _curve(p, kind: str) -> list[walk_path.Footstep]:
    if kind == "quarter":
        a = np.linspace(0.0, np.pi / 2, 9)
        return footsteps.from_path(p, np.column_stack([2.0 - 2.0 * np.cos(a), 2.0 * np.sin(a)]), facing=np.pi / 2)
    z = np.linspace(0.0, 6.0, 13)
    return footsteps.from_path(p, np.column_stack([0.5 * np.sin(z * np.pi / 3), z]), facing=S_END_HEADING)


def _leg(w: walk_path.Walk, tg: walk_path.FrameTargets, side: str) -> float:
    """Hip-to-ankle distance (m) of one leg in a frame's targets."""
    yaw = float(np.arctan2(tg.pelvis[0, 2], tg.pelvis[2, 2]))
    return float(np.linalg.norm(w._hip(tg.pelvis[:3, 3], yaw, side) - walk_path._ankle(w.p, tg.feet[side], side)))


@pytest.mark.parametrize("kind", ["quarter", "s-curve"])
def test_stance_leg_keeps_the_1d_length_and_the_pelvis_dips_at_double_support(kind):
    """Eq. 5.14 on every steady step (11 samples): the stance leg is ω(t) of the underlying 1-D
    walk (1e-9 m) though the centre site is displaced from it (the Boulic height alone misses it
    by up to 6.7 mm on the quarter circle); no leg stretches beyond MAX_LEG of its length; the
    pelvis is lowest around the heel strike and double support and highest in mid stance."""
    _, p = figure_and_params("male:50")
    steps = _curve(p, kind)
    walk = walk_path.Walk(steps, p)
    one = walk.underlying
    assert len(one.steps) == len(steps) and one.underlying is None
    displaced = 0.0
    for j in range(3, len(steps) - 2):
        t0, t1 = walk.land[j - 1], walk.land[j]
        u = np.linspace(0.0, 1.0, 21)[:-1]
        h = []
        for t in t0 + u * (t1 - t0):
            tg, tg1 = walk.at(t), one.at(t)
            side = steps[j - 1].side
            assert _leg(walk, tg, side) == pytest.approx(_leg(one, tg1, side), abs=1e-9)
            for s in ("left", "right"):
                if tg.phase[s] != "swing":
                    assert _leg(walk, tg, s) <= MAX_LEG * p.leg_length + 1e-9
            displaced = max(displaced, abs(tg.pelvis[1, 3] - tg1.pelvis[1, 3]))
            h.append(tg.pelvis[1, 3])
        h = np.array(h)
        ds = (u <= 2.0 * DOUBLE_SUPPORT) | (u >= 0.9)  # around the heel strike that begins it
        mid = (u >= 0.4) & (u <= 0.8)
        assert int(np.argmin(h)) in np.flatnonzero(ds), f"step {j}: lowest at u = {u[np.argmin(h)]:.2f}"
        assert int(np.argmax(h)) in np.flatnonzero(mid), f"step {j}: highest at u = {u[np.argmax(h)]:.2f}"
        assert h.max() - h.min() > 0.01  # the 1-D profile's dip survives (about 3-4 cm)
    assert displaced > 0.001  # the 2-D centre site is not at the 1-D height: the rule acts


def test_straight_path_is_its_own_1d_walk():
    """A straight path unrolls onto itself, so its pelvis is the 1-D pelvis (the book's check)."""
    _, p = figure_and_params("male:50")
    walk = walk_path.Walk(footsteps.straight(p, 2.5, 0.3, -0.2, 0.9), p)
    for a, b in zip(walk.steps, walk.underlying.steps):
        assert np.allclose([a.x, a.z, a.psi], [b.x, b.z, b.psi], atol=1e-12) and a.side == b.side
    for t in np.arange(0.0, walk.duration, 0.05):
        assert np.allclose(walk.at(t).pelvis, walk.underlying.at(t).pelvis, atol=1e-9)


def test_unrolled_steps_keep_the_step_lengths():
    """The 1-D steps are the 2-D centre-site steps unrolled: each within 1 % of its arc δ (0.4 %
    measured), all facing along one line."""
    _, p = figure_and_params("male:50")
    walk = walk_path.Walk(_curve(p, "quarter"), p)
    one = walk.underlying
    for k in range(1, len(walk.keys)):
        delta = walk_path._arc_length(walk.keys[k - 1], walk.keys[k], walk.key_dir[k - 1], walk.key_dir[k])
        d1 = float(np.linalg.norm(one.keys[k] - one.keys[k - 1]))
        assert d1 == pytest.approx(delta, rel=0.01, abs=1e-6)
        assert abs(one.key_dir[k] - one.key_dir[0]) < 1e-12


def test_solved_stance_leg_never_over_extends():
    """The baked quarter circle (IK): no stance leg's hip-ankle distance exceeds its standing length."""
    fig, p, steps, postures, targets = baked("male:50", "quarter")
    for po, tg in zip(postures, targets):
        po.apply_to(fig)
        for s in ("left", "right"):
            if tg.phase[s] != "swing":
                hip, ankle = fig.site_world("pelvis", f"{s}_hip")[:3, 3], fig.site_world(f"{s}_shank", "ankle")[:3, 3]
                assert np.linalg.norm(hip - ankle) <= p.leg_length + 1e-4
