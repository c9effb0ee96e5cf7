"""Record: a live drag turned into key tracks through the document API; the take replays to the
posture that was seen; undo removes it; the rate and the driven parts are honoured."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.document import Document
from jackpy.document.effectors import find_effectors
from jackpy.motion import cast
from jackpy.motion.bake import Baker
from jackpy.motion.cast import loop_for
from jackpy.motion.recorder import Recorder
from jackpy.peabody.model import Environment

DT = 1 / 30


def make_doc() -> Document:
    env = Environment()
    env.add(cast.make_figure("jack"))
    return Document(env)


def drag_hand(doc: Document, rec: Recorder, frames: int = 45) -> list[tuple[float, np.ndarray]]:
    """Drag jack's right hand forward and up, one operator move and one step per frame; returns
    (timeline time, palm position) of each frame as shown."""
    fig = doc.env.figures["jack"]
    g = doc.ensure_goal(fig, find_effectors(fig)["right_hand"])
    start = g.manip.copy()
    seen = []
    for k in range(1, frames + 1):
        m = start.copy()
        m[:3, 3] += np.array([0.0, 0.25, 0.30]) * k / frames
        doc.move_goal(g, m)
        doc.step(DT)
        rec.tick(DT)
        palm = fig.site_world(*doc.loops["jack"].anatomy.hands["right"].palm)[:3, 3]
        seen.append((rec.time, palm.copy()))
    doc.end_behavior_drag()
    return seen


def test_a_drag_becomes_keys_at_the_rate_and_replays_to_what_was_seen():
    doc = make_doc()
    rec = Recorder(doc, "jack", rate=10.0)
    rec.start()
    seen = drag_hand(doc, rec)
    tracks = rec.stop()
    parts = {t.part for t in tracks}
    assert "hand.right" in parts and "hand.left" not in parts and "head" not in parts
    hand = next(t for t in tracks if t.part == "hand.right")
    times = [t for t, _ in hand.keys]
    assert times[0] == 0.0 and times[-1] == pytest.approx(45 * DT)
    assert len(times) == pytest.approx(45 * DT * 10 + 1, abs=1)  # 10 keys per second
    assert np.all(np.diff(times) >= 0.1 - 1e-9)
    assert doc.time == pytest.approx(45 * DT) and doc.dirty
    # the keys hold what was seen, and the timeline replays the take to that posture
    for t, v in hand.keys[1:]:
        shown = min(seen, key=lambda s: abs(s[0] - t))
        assert np.linalg.norm(v[:3, 3] - shown[1]) < 1e-9
    fig = doc.env.figures["jack"]
    replay_env = Environment()
    twin = replay_env.add(cast.make_figure("jack"))
    baker = Baker(doc.timeline, {"jack": loop_for(twin)}, replay_env, fps=10.0)
    frames = baker.bake()
    end = frames[-1]["jack"]
    end.apply_to(twin)
    palm = twin.site_world(*loop_for(twin).anatomy.hands["right"].palm)[:3, 3]
    assert np.linalg.norm(palm - seen[-1][1]) < 0.01
    assert fig is doc.env.figures["jack"]


def test_record_is_one_undo_step_and_keeps_keys_outside_the_take():
    doc = make_doc()
    rec = Recorder(doc, "jack", rate=5.0, parts=["hand.right", "pelvis"])
    doc.time = 2.0
    rec.start()
    drag_hand(doc, rec, frames=15)
    assert doc.timeline is None  # nothing lands on the timeline until the take ends
    rec.stop()
    hand = doc.timeline.track("jack", "hand.right", create=False)
    assert {t.part for t in doc.timeline.tracks} == {"hand.right", "pelvis"}  # named parts, moved or not
    assert hand.keys[0][0] == 2.0 and hand.keys[-1][0] == pytest.approx(2.5)
    assert doc.undo() and doc.timeline.tracks == []
    assert doc.redo() and len(doc.timeline.track("jack", "hand.right", create=False).keys) == len(hand.keys)
    # a second take over [2.2, 2.4] replaces only its own span
    before = [t for t, _ in doc.timeline.track("jack", "hand.right", create=False).keys]
    doc.time = 2.2
    rec2 = Recorder(doc, "jack", rate=5.0, parts=["hand.right"])
    rec2.start()
    for _ in range(6):
        doc.step(DT)
        rec2.tick(DT)
    rec2.stop()
    after = [t for t, _ in doc.timeline.track("jack", "hand.right", create=False).keys]
    assert [t for t in after if not 2.2 - 1e-9 <= t <= 2.4 + 1e-9] == [t for t in before if not 2.2 - 1e-9 <= t <= 2.4 + 1e-9]


def test_nothing_driven_records_nothing_and_bad_arguments_are_refused():
    doc = make_doc()
    rec = Recorder(doc, "jack")
    rec.start()
    for _ in range(10):
        doc.step(DT)
        rec.tick(DT)
    assert rec.stop() == [] and doc.timeline is None and doc.undo_stack.undo_label is None
    with pytest.raises(ValueError, match="rate"):
        Recorder(doc, "jack", rate=0)
    with pytest.raises(ValueError, match="part"):
        Recorder(doc, "jack", parts=["tail"])
    with pytest.raises(ValueError, match="behavior loop"):
        Recorder(doc, "nobody")


def test_a_flock_session_becomes_keys_that_replay_its_reach():
    """The shipped Flock recording (a two-handed reach, 3 s) driven into the document's figure
    and recorded at 5 Hz: both palms and the pelvis are recorded; the timeline replays the reach."""
    from pathlib import Path

    from jackpy.behaviors.sensor_drive import SensorDrive
    from jackpy.devices.recording import read_recording
    from jackpy.devices.sensors import sensor_config_from_dict
    from jackpy.motion.recorder import record_recording

    reach = read_recording(Path(__file__).resolve().parents[2] / "examples" / "flock" / "reach.jsonl")
    doc = make_doc()
    loop = doc.loops["jack"]
    drive = SensorDrive(loop, None, sensor_config_from_dict(reach.header["sensors"]))
    tracks = record_recording(doc, drive, reach, rate=5.0, every=10)
    parts = {t.part for t in tracks}
    assert {"hand.left", "hand.right"} <= parts
    hand = next(t for t in tracks if t.part == "hand.right")
    assert hand.keys[0][0] == 0.0 and hand.keys[-1][0] == pytest.approx(2.99, abs=1e-6)
    assert len(hand.keys) == pytest.approx(2.99 * 5 + 1, abs=1)
    fig = doc.env.figures["jack"]
    reached = {side: fig.site_world(*loop.anatomy.hands[side].palm)[:3, 3].copy() for side in ("left", "right")}
    replay_env = Environment()
    twin = replay_env.add(cast.make_figure("jack"))
    twin_loop = loop_for(twin)
    Baker(doc.timeline, {"jack": twin_loop}, replay_env, fps=10.0).bake()[-1]["jack"].apply_to(twin)
    for side, p in reached.items():
        assert np.linalg.norm(twin.site_world(*twin_loop.anatomy.hands[side].palm)[:3, 3] - p) < 0.02
