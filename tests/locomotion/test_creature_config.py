"""Every walking and pronking parameter has a named default (pinned here)."""

from __future__ import annotations

from jackpy.locomotion.config import PronkConfig, WalkConfig

WALK = {"gait": "auto", "cycle_time": 1.0, "speed": 0.2, "duty_trot": 0.6, "duty_wave": 0.75,
        "bounciness": 0.005, "body_height": None, "swing_clearance": 0.03, "max_slope_deg": 35.0,
        "foot_radius": 0.03, "max_turn_rate": 0.8, "slow_down_distance": 0.3, "body_clearance_min": 0.01,
        "terrain_sample_radius": 0.1, "fps": 30.0, "ik_tolerance": 1e-4, "reach_fraction": 0.95,
        "full_extension_fraction": 0.97}
PRONK = {"jump_height": 0.06, "jump_distance": 0.08, "crouch_fraction": 0.8, "max_leg_force_factor": 4.0,
         "substeps": 8, "fps": 30.0, "flight_foot_lift": 0.02, "landing_speed_margin": 0.05}


def test_walk_defaults():
    assert WalkConfig().to_dict() == WALK


def test_pronk_defaults():
    assert PronkConfig().to_dict() == PRONK


def test_with_changes_one_value():
    c = WalkConfig().with_(speed=0.3)
    assert c.speed == 0.3 and c.cycle_time == 1.0
