"""Weight and velocity functions of a motion ([SH4] §4.3; behaviors.md §4.2-4.3).

``u = (t - t0) / (t1 - t0)`` in [0, 1] is the motion's normalised time.

- A **weight function** scales the motion's maximum weight: ``constant`` 1; ``increase`` u (0 at the
  start, the maximum at the end); ``decrease`` 1 - u; ``ease`` (ease in/ease out) 0 at both ends and
  the maximum halfway, (1 - cos 2πu) / 2.
- A **velocity function** gives the progress ``s(u)`` along the path from the start to the end pose
  (the integral of the normalised velocity): ``constant`` s = u; ``increase`` s = u² (starts slow);
  ``decrease`` s = 1 - (1 - u)² (starts fast); ``ease`` s = (1 - cos πu) / 2 (slow, fastest halfway,
  zero velocity at both ends).
"""

from __future__ import annotations

import math

WEIGHT_FUNCTIONS = ("constant", "increase", "decrease", "ease")
VELOCITY_FUNCTIONS = ("constant", "increase", "decrease", "ease")


def normalised_time(t: float, t0: float, t1: float) -> float:
    """u in [0, 1] of time ``t`` (s) in [t0, t1]; a zero-length interval is 1 from t0 on."""
    if t1 <= t0:
        return 1.0 if t >= t0 else 0.0
    return min(1.0, max(0.0, (t - t0) / (t1 - t0)))


def weight_factor(name: str, u: float) -> float:
    """The weight function ``name`` at normalised time ``u``, in [0, 1]."""
    if name == "constant":
        return 1.0
    if name == "increase":
        return u
    if name == "decrease":
        return 1.0 - u
    if name == "ease":
        return 0.5 * (1.0 - math.cos(2.0 * math.pi * u))
    raise ValueError(f"weight function must be one of {WEIGHT_FUNCTIONS}, not {name!r}")


def progress(name: str, u: float) -> float:
    """The velocity function ``name``'s progress s(u) along the path, s(0) = 0, s(1) = 1, monotone."""
    if name == "constant":
        return u
    if name == "increase":
        return u * u
    if name == "decrease":
        return 1.0 - (1.0 - u) ** 2
    if name == "ease":
        return 0.5 * (1.0 - math.cos(math.pi * u))
    raise ValueError(f"velocity function must be one of {VELOCITY_FUNCTIONS}, not {name!r}")


def velocity(name: str, u: float) -> float:
    """ds/du of the velocity function ``name`` (the green line's shape)."""
    if name == "constant":
        return 1.0
    if name == "increase":
        return 2.0 * u
    if name == "decrease":
        return 2.0 * (1.0 - u)
    if name == "ease":
        return 0.5 * math.pi * math.sin(math.pi * u)
    raise ValueError(f"velocity function must be one of {VELOCITY_FUNCTIONS}, not {name!r}")
