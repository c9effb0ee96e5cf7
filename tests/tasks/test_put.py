"""put on / put in ([SH6] §6.2.4): the block ends face down on the table top, within 1 mm, not
interpenetrating, not attached, the hand returns; moving the table carries it; a too-small
container fails with "does not fit" and the failure hook runs."""

import numpy as np
import pytest

from jackpy.tasks import checklist


@pytest.fixture(scope="module")
def result(put_scene):
    return checklist.load(put_scene.parent / "put.task").run(put_scene)


def test_too_small_container_fails_and_hook_runs(result):
    put_in = result.reports[0] if result.reports[0].command.startswith("Put block in") else \
        next(r for r in result.reports if r.command.startswith("Put block in"))
    assert put_in.status == "failed" and "does not fit" in put_in.reason
    hook = next(r for r in result.reports if r.command == "Look smallbox")
    assert hook.status == "done" and hook.start == pytest.approx(put_in.end)
    put_on = next(r for r in result.reports if r.command == "Put block on table")
    assert put_on.start >= hook.end - 1e-9  # the next line waits for the hook


def test_block_rests_on_the_table(result):
    put_on = next(r for r in result.reports if r.command == "Put block on table")
    assert put_on.status == "done", put_on.reason
    env = result.env
    block, table = env.figures["block"], env.figures["table"]
    v = block.world_mesh().vertices
    assert v[:, 1].min() == pytest.approx(0.75, abs=0.001)  # on the top surface
    assert np.allclose(block.location[:3, :3] @ [0, -1, 0], [0, -1, 0], atol=1e-9)  # face down
    tv = table.world_mesh().vertices
    top = tv[tv[:, 1] > 0.749]
    assert top[:, 0].min() <= v[:, 0].min() and v[:, 0].max() <= top[:, 0].max()
    assert top[:, 2].min() <= v[:, 2].min() and v[:, 2].max() <= top[:, 2].max()
    assert v[:, 1].min() >= 0.75 - 1e-9  # not into the table
    # not attached to the hand
    for loop in result.loops.values():
        for hs in loop.state.hands.values():
            assert all(getattr(a.obj, "obj", None) is not block for a in hs.attached)
    # the hand returned to where it was before the put
    assert put_on.checks["Return hand: error_m"] <= 0.01
    # moving the table carries the block
    before = block.location.copy()
    T = table.location.copy()
    T[:3, 3] += [0.2, 0.0, -0.1]
    result.kb.move_object("table", T)
    assert np.allclose(block.location[:3, 3], before[:3, 3] + [0.2, 0.0, -0.1])


def test_hand_moving_after_release_leaves_the_block(result):
    block = result.env.figures["block"]
    before = block.location.copy()
    loop = result.loops["John"]
    for _ in range(3):
        result.timeline.apply(result.timeline.duration + 1.0, result.loops, result.env)
        loop.step()
    assert np.allclose(block.location, before)
