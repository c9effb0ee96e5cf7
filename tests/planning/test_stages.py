"""Staged posture planning (issue 16): arm -> torso -> knees -> step, each stage tried only when the
one before fails, on the 50th-percentile man in free space; and ``jackpy reach`` on the example
workplace."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import numpy as np
import pytest

from jackpy.body.human import make_human
from jackpy.cli import main
from jackpy.planning.stages import staged_reach

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json"


@pytest.fixture(scope="module")
def man():
    return make_human("male", 50)


def _shoulder_and_arm(f):
    sh = f.site_world("right_clavicle", "shoulder")[:3, 3]
    return sh, float(np.linalg.norm(f.site_world("right_palm", "grip")[:3, 3] - sh))


def test_twenty_cm_beyond_the_arm_is_reached_by_the_torso(man):
    sh, arm = _shoulder_and_arm(man)
    target = sh + np.array([0.0, -0.1, np.sqrt((arm + 0.2) ** 2 - 0.01)])
    s = staged_reach(man, target, "right")
    assert [a for a, _ in s.attempts] == ["arm", "torso"]
    assert not s.attempts[0][1].reached and s.attempts[0][1].shortfall > 0.15
    assert s.stage == "torso" and s.result.reached and s.result.com_margin <= 0.0
    assert "torso stage" in s.describe()


def test_forty_cm_below_the_hand_is_reached_with_the_knees_bent(man):
    hand = man.site_world("right_palm", "grip")[:3, 3]
    target = hand + np.array([0.0, -0.4, 0.0])
    s = staged_reach(man, target, "right", stages=("arm", "torso", "pelvis"))
    assert [a for a, _ in s.attempts] == ["arm", "torso", "pelvis"]
    assert not s.attempts[0][1].reached and not s.attempts[1][1].reached
    assert s.stage == "pelvis" and s.result.reached and s.result.com_margin <= 0.0
    assert "pelvis stage (knees bent" in s.describe()
    c = copy.deepcopy(man)
    s.result.posture.apply(c)
    for side in ("left", "right"):  # the feet stay where they stand
        assert np.linalg.norm(c.site_world(f"{side}_foot", "heel")[:3, 3]
                              - man.site_world(f"{side}_foot", "heel")[:3, 3]) <= 0.01
    assert max(c.joint("right_knee").displacement[0], c.joint("left_knee").displacement[0]) > np.radians(20)
    assert np.linalg.norm(c.site_world("right_palm", "grip")[:3, 3] - target) <= 0.005


def test_one_metre_away_is_reached_by_a_step(man):
    sh, _ = _shoulder_and_arm(man)
    target = sh + np.array([0.0, -0.1, 1.0])
    s = staged_reach(man, target, "right", stages=("arm", "torso", "step"))
    assert [a for a, _ in s.attempts] == ["arm", "torso", "step"]
    assert s.stage == "step" and s.result.reached and s.result.steps >= 1
    assert not any(r.reached for _, r in s.attempts[:-1])


def test_reach_command_names_the_blocking_object(tmp_path, capsys):
    rc = main(["reach", str(EXAMPLE), "--figure", "male:95", "--target", "desk.far_corner", "-o", str(tmp_path)])
    assert rc == 0
    res = json.loads((tmp_path / "reach.json").read_text())
    assert res["stage"] is None and not res["reached"]
    assert res["attempts"][0]["verdict"] == "blocked" and res["attempts"][0]["blocked_by"] == "partition"
    assert "blocked by partition" in capsys.readouterr().out
    assert [st["stage"] for st in res["stages"]] == ["arm"] and res["stages"][0]["text"] == "arm only"
