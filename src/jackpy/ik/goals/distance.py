"""Distance goal: the site origin ``r`` kept at distance ``radius`` from a centre ``c``.

``d = |r - c|``. ``mode`` says which side of the sphere counts:

- ``"inside"``: ``P = max(0, d - radius)^2`` (within reach of a point: a tool kept near a part);
- ``"outside"``: ``P = max(0, radius - d)^2`` (clear of a point: a hand kept off a hot surface);
- ``"surface"``: ``P = (d - radius)^2`` (exactly at the distance, an equality).

The one-sided forms are C1 across the sphere and pull nothing on the allowed side, like the
half-space goal (3.23-3.24). The residual's Jacobian is ``± u^T dr/dq`` with ``u = (r - c)/d``;
within 1e-9 m of the centre ``u`` is undefined and the Jacobian is taken as zero (no NaN).
"""

from __future__ import annotations

import numpy as np

from jackpy.ik.goals.base import Chain, Context, GoalEval, SiteGoal, point3

MODES = ("inside", "outside", "surface")


class Distance(SiteGoal):
    """Keep the origin of ``site`` within, beyond or exactly at ``radius`` (m) of ``centre`` (world, m)."""

    kind = "distance"
    targets = ("centre",)
    params = ("radius", "mode")

    def __init__(self, site: str, centre: np.ndarray, radius: float = 0.1, mode: str = "inside",
                 chain: Chain = None, weight: float = 1.0, name: str | None = None) -> None:
        super().__init__(site, chain, weight, name)
        self.centre = point3(centre)
        self.radius = self.check_param("radius", radius)
        self.mode = self.check_param("mode", mode)

    @classmethod
    def check_param(cls, name: str, value: object) -> object:
        if name == "radius":
            r = float(value)  # type: ignore[arg-type]
            if not (np.isfinite(r) and r >= 0.0):
                raise ValueError(f"distance radius must be a finite number >= 0 m, not {value!r}")
            return r
        if name == "mode" and value not in MODES:
            raise ValueError(f"distance mode must be one of {', '.join(MODES)}, not {value!r}")
        return super().check_param(name, value)

    def evaluate(self, ctx: Context) -> GoalEval:
        r = ctx.site(self.seg, self.location)[:3, 3]
        v = r - self.centre
        d = float(np.linalg.norm(v))
        excess = d - self.radius
        if self.mode == "inside":
            f = max(excess, 0.0)
        elif self.mode == "outside":
            f = max(-excess, 0.0)
        else:
            f = excess
        if f == 0.0 or d < 1e-9:
            return GoalEval(np.array([f]), np.zeros((1, ctx.cols.size)), metres=abs(f))
        sign = -1.0 if self.mode == "outside" else 1.0
        J = sign * ((v / d) @ ctx.point_jacobian(self.seg, r))
        return GoalEval(np.array([f]), J[None, :], metres=abs(f))

    def set_frame(self, frame: np.ndarray) -> None:
        """The centre is the frame's origin."""
        self.centre = point3(frame)
