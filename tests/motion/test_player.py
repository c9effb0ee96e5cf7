"""Playback of a document's timeline, headless: baked postures shown, scrub equals the baked frame,
edits are undoable document commands, time runs at the real rate."""

from __future__ import annotations

import json

import numpy as np

from jackpy.document import Document
from jackpy.motion import cast
from jackpy.motion.bake import Posture
from jackpy.motion.player import Player, load_into
from jackpy.peabody.model import Environment


def motion_file(tmp_path, figure):
    data = {"jackpy_motion": 1, "timeline": {
        "motions": [{"kind": "com", "figure": figure, "t0": 0.0, "t1": 0.3, "x": 0.2},
                    {"kind": "foot", "figure": figure, "side": "right", "t0": 0.3, "t1": 0.6,
                     "displacement": [0, 0, 0.15], "height": 0.05}],
        "duration": 0.7}}
    p = tmp_path / "m.motion.json"
    p.write_text(json.dumps(data))
    return p


def make_doc():
    env = Environment()
    env.add(cast.make_figure("jack"))
    return Document(env)


def test_play_scrub_and_undo(tmp_path):
    doc = make_doc()
    load_into(doc, str(motion_file(tmp_path, "jack")))
    fig = doc.env.figures["jack"]
    start = Posture.of(fig)
    player = Player(doc, fps=10)
    player.play()
    for _ in range(40):
        player.update(0.05, budget_s=1.0)
    assert not player.playing and player.time == doc.timeline.duration  # ran to the end and stopped
    assert not Posture.of(fig).same(start)  # the figure moved
    player.scrub(0.35)
    assert Posture.of(fig).same(player.baker.frames[3]["jack"])  # the baked frame, to the bit
    m = doc.timeline.motions[1]
    player.shift(m, 0.2)
    assert m.t0 == 0.5
    assert doc.undo()
    assert doc.timeline.motions[1].t0 == 0.3  # undone through the document
    player.ensure_baker()  # the edit and its undo re-bake
    assert player.baker.n_frames == 8


def test_playback_drops_frames_rather_than_slowing_time(tmp_path):
    doc = make_doc()
    load_into(doc, str(motion_file(tmp_path, "jack")))
    player = Player(doc, fps=10)
    player.play()
    player.update(0.5, budget_s=0.0)  # half a second passed and almost nothing is baked
    assert player.time == 0.5


def test_load_into_adds_missing_figures(tmp_path):
    doc = Document(Environment())
    load_into(doc, str(motion_file(tmp_path, "newcomer")))
    assert "newcomer" in doc.env.figures and "newcomer" in doc.loops
    assert np.isclose(doc.timeline.duration, 0.7)
