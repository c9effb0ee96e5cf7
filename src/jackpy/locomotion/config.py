"""Every walking and pronking parameter, named, with its default (each pinned by
``tests/locomotion/test_creature_config.py``). Units: metres, seconds, radians unless named.

The thesis gives no numbers (digest §8, §11.17); these are our choices, documented in
docs/creatures.md.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields, replace
from typing import Any


@dataclass(frozen=True)
class WalkConfig:
    """Parameters of kinematic walking (Sims Ch. 9-10)."""

    #: "auto" (trot for up to 4 legs, wave for more), "wave", "tripod" (= trot), "trot", "pronk"
    gait: str = "auto"
    #: stride cycle time T (s): each foot steps once per cycle
    cycle_time: float = 1.0
    #: body speed along the path (m/s); stride length = speed x cycle_time
    speed: float = 0.2
    #: duty factor of the trot family (fraction of the cycle a foot is down)
    duty_trot: float = 0.6
    #: duty factor of the wave family
    duty_wave: float = 0.75
    #: amplitude (m) of the gait-phased vertical bounce added to the body path
    bounciness: float = 0.005
    #: body height above the terrain (m); None: the figure's own, from its posture in the file
    body_height: float | None = None
    #: swing clearance (m) above the highest terrain between the old and new footholds
    swing_clearance: float = 0.03
    #: steepest steppable slope (degrees) for forbidden zones
    max_slope_deg: float = 35.0
    #: foot radius (m): width of the forbidden band below a steep slope
    foot_radius: float = 0.03
    #: largest turning rate of the body heading (rad/s)
    max_turn_rate: float = 0.8
    #: distance (m) over which the speed ramps down before the goal
    slow_down_distance: float = 0.3
    #: least clearance (m) kept between the body's surface and the terrain
    body_clearance_min: float = 0.01
    #: radius (m) of the terrain samples under the body that set its height and pitch
    terrain_sample_radius: float = 0.1
    #: frames per second of the baked output
    fps: float = 30.0
    #: IK tolerance on each foot (m)
    ik_tolerance: float = 1e-4
    #: the body is lowered so no foot target lies beyond this fraction of its leg's full length
    reach_fraction: float = 0.95
    #: Sims' full-extension region: a leg beyond this fraction of its full length uses the fallback
    full_extension_fraction: float = 0.97

    def with_(self, **kw: Any) -> "WalkConfig":
        return replace(self, **kw)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def names(cls) -> list[str]:
        return [f.name for f in fields(cls)]


@dataclass(frozen=True)
class PronkConfig:
    """Parameters of pronking (Sims Ch. 11): all feet hop together."""

    #: apex height of each jump above takeoff (m)
    jump_height: float = 0.06
    #: horizontal distance of each jump (m)
    jump_distance: float = 0.08
    #: crouch height: hip height above the feet (fraction of the figure's standing height) where the
    #: landing phase stops the fall
    crouch_fraction: float = 0.8
    #: maximum force of one leg, as a multiple of the body weight over the number of legs
    max_leg_force_factor: float = 4.0
    #: simulation steps per animation frame (dt = 1 / (fps x substeps))
    substeps: int = 8
    #: frames per second of the baked output
    fps: float = 30.0
    #: flight-foot spline: height (m) of its middle point above the straight line
    flight_foot_lift: float = 0.02
    #: documented bound on the body's vertical speed at touchdown (m/s): sqrt(2 g (jump_height +
    #: 0.05 m)); the test checks every landing against it
    landing_speed_margin: float = 0.05

    def with_(self, **kw: Any) -> "PronkConfig":
        return replace(self, **kw)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)
