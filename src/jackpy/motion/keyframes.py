"""Keyframes of goal targets ([proposal]: designers expect them; the book's motions have none).

A :class:`KeyTrack` stores, for one part of one figure, its goal target at key times; between keys
the goal interpolates (positions ``linear`` or ``cubic`` Catmull-Rom, orientations slerp) and the
behaviors and IK produce the posture, as for a motion. A track acts from its first key to its last;
after the last key the goal stays where the last key put it. Parts and their key values:

- ``hand.left`` / ``hand.right``: the palm-site pose (4x4, world) — the hand goal;
- ``foot.left`` / ``foot.right``: the ball-site pose (4x4) — the toe goal (foot held, heel free);
- ``pelvis``: the pelvis-site world rotation (3x3);
- ``com``: the balance parameters [x, z] (x = share of weight on the right foot);
- ``head`` / ``eyes``: the fixation point [x, y, z];
- ``joint:NAME``: **joint-angle keys** for a single joint (its displacements, rad/m), written
  directly into the joint before the solve (clamped to its limits); the one place a timeline sets
  angles, so a goal whose chain crosses that joint may still move it.
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from jackpy import jsonfile
from jackpy.motion.interpolate import catmull_rom, lerp, slerp

if TYPE_CHECKING:
    from jackpy.behaviors.loop import BehaviorLoop

POSE_PARTS = ("hand.left", "hand.right", "foot.left", "foot.right")
PARTS = (*POSE_PARTS, "pelvis", "com", "head", "eyes")
INTERPOLATIONS = ("linear", "cubic")


def _shape(part: str) -> tuple[int, ...] | None:
    if part in POSE_PARTS:
        return (4, 4)
    if part == "pelvis":
        return (3, 3)
    if part == "com":
        return (2,)
    if part in ("head", "eyes"):
        return (3,)
    return None  # a joint: its DOF count


@dataclass
class KeyTrack:
    """Keys ``(t, value)`` (sorted by time) of goal targets of ``part`` of figure ``figure``."""

    figure: str
    part: str
    keys: list[tuple[float, np.ndarray]] = field(default_factory=list)
    interpolation: str = "linear"
    enabled: bool = True

    def __post_init__(self) -> None:
        if self.part not in PARTS and not self.part.startswith("joint:"):
            raise ValueError(f"key track part must be one of {PARTS} or joint:NAME, not {self.part!r}")
        if self.interpolation not in INTERPOLATIONS:
            raise ValueError(f"interpolation must be one of {INTERPOLATIONS}, not {self.interpolation!r}")
        self.keys = sorted(((float(t), np.array(v, dtype=float)) for t, v in self.keys), key=lambda k: k[0])

    @property
    def is_joint(self) -> bool:
        return self.part.startswith("joint:")

    @property
    def span(self) -> tuple[float, float]:
        return (self.keys[0][0], self.keys[-1][0]) if self.keys else (0.0, 0.0)

    def set_key(self, t: float, value: np.ndarray) -> None:
        """Add a key at ``t`` (s), replacing one at the same time."""
        value = np.array(value, dtype=float)
        shape = _shape(self.part)
        if shape is not None and value.shape != shape:
            raise ValueError(f"{self.part} key must have shape {shape}, not {value.shape}")
        self.keys = [k for k in self.keys if abs(k[0] - t) > 1e-9]
        bisect.insort(self.keys, (float(t), value), key=lambda k: k[0])

    def remove_key(self, t: float) -> None:
        self.keys = [k for k in self.keys if abs(k[0] - t) > 1e-9]

    def value(self, t: float) -> np.ndarray:
        """The interpolated target at ``t`` (clamped to the first and last keys)."""
        times = [k[0] for k in self.keys]
        if t <= times[0]:
            return self.keys[0][1].copy()
        if t >= times[-1]:
            return self.keys[-1][1].copy()
        i = bisect.bisect_right(times, t) - 1
        (ta, a), (tb, b) = self.keys[i], self.keys[i + 1]
        s = (t - ta) / (tb - ta) if tb > ta else 1.0
        if self.part in POSE_PARTS:
            out = np.eye(4)
            out[:3, :3] = slerp(a[:3, :3], b[:3, :3], s)
            out[:3, 3] = self._position(i, s, [k[1][:3, 3] for k in self.keys])
            return out
        if self.part == "pelvis":
            return slerp(a, b, s)
        return self._position(i, s, [k[1] for k in self.keys])

    def _position(self, i: int, s: float, pts: list[np.ndarray]) -> np.ndarray:
        if self.interpolation == "linear":
            return lerp(pts[i], pts[i + 1], s)
        p0 = pts[i - 1] if i > 0 else 2 * pts[i] - pts[i + 1]
        p3 = pts[i + 2] if i + 2 < len(pts) else 2 * pts[i + 1] - pts[i]
        return catmull_rom(p0, pts[i], pts[i + 1], p3, s)

    def apply(self, loop: "BehaviorLoop", t: float) -> None:
        """Write the target at ``t`` into the figure's goals (only within the track's span)."""
        if not self.enabled or not self.keys or not self.span[0] <= t <= self.span[1]:
            return
        write(loop, self.part, self.value(t))

    def to_dict(self) -> dict[str, Any]:
        return {"figure": self.figure, "part": self.part, "interpolation": self.interpolation,
                "enabled": self.enabled, "keys": [{"t": t, "value": v.tolist()} for t, v in self.keys]}

    @classmethod
    def from_dict(cls, d: dict[str, Any], where: str = "keyframes") -> "KeyTrack":
        d = jsonfile.obj(d, where)
        part = jsonfile.string(jsonfile.required(d, "part", where), jsonfile.key(where, "part"))
        shape = _shape(part)
        keys = []
        kw = jsonfile.key(where, "keys")
        for k, kd in enumerate(jsonfile.arr(d.get("keys", []), kw)):
            kd = jsonfile.obj(kd, jsonfile.key(kw, k))
            t = jsonfile.num(jsonfile.required(kd, "t", jsonfile.key(kw, k)), jsonfile.key(jsonfile.key(kw, k), "t"), 0.0)
            vw = jsonfile.key(jsonfile.key(kw, k), "value")
            v = jsonfile.required(kd, "value", jsonfile.key(kw, k))
            if shape is not None and len(shape) == 2:
                val = jsonfile.matrix(v, vw, *shape)
            elif shape is not None:
                val = jsonfile.vector(v, vw, shape[0])
            else:
                val = np.array([jsonfile.num(x, jsonfile.key(vw, j)) for j, x in enumerate(jsonfile.arr(v, vw))])
            keys.append((t, val))
        try:
            return cls(jsonfile.string(jsonfile.required(d, "figure", where), jsonfile.key(where, "figure")), part,
                       keys, jsonfile.string(d.get("interpolation", "linear"), jsonfile.key(where, "interpolation"),
                                             INTERPOLATIONS),
                       jsonfile.boolean(d.get("enabled", True), jsonfile.key(where, "enabled")))
        except ValueError as exc:
            raise jsonfile.Invalid(where, str(exc)) from None


def capture(loop: "BehaviorLoop", part: str) -> np.ndarray:
    """The current target of ``part`` read from the figure's posture (what "set key" stores)."""
    fig, a, st = loop.figure, loop.anatomy, loop.state
    if part.startswith("hand."):
        return fig.site_world(*a.hands[part[5:]].palm)
    if part.startswith("foot."):
        return fig.site_world(*a.feet[part[5:]].ball)
    if part == "pelvis":
        return fig.site_world(a.pelvis, a.pelvis_site)[:3, :3]
    if part == "com":
        return np.array(st.balance, dtype=float)
    if part in ("head", "eyes"):
        tgt = st.head_target if part == "head" else st.eyes_target
        if tgt is not None:
            return np.array(tgt, dtype=float)
        view = fig.site_world(*a.view)
        fwd = fig.world_transforms()[a.view[0]][:3, :3] @ a.view_forward
        return view[:3, 3] + 2.0 * fwd / np.linalg.norm(fwd)
    if part.startswith("joint:"):
        return fig.joint(part[6:]).displacement.copy()
    raise ValueError(f"no such key part {part!r}")


def write(loop: "BehaviorLoop", part: str, value: np.ndarray) -> None:
    """Set the goal of ``part`` to ``value`` (see the module docstring for the value of each part)."""
    st = loop.state
    if part.startswith("hand."):
        hs = st.hands[part[5:]]
        hs.goal, hs.orient, hs.rules, hs.local = np.array(value, dtype=float), True, False, None
    elif part.startswith("foot."):
        side = part[5:]
        if st.root == side:
            loop.set_root("left" if side == "right" else "right")
        st.root_claimed = True
        fs = st.feet[side]
        fs.target, fs.mode, fs.heel = np.array(value, dtype=float), "hold", "free"
    elif part == "pelvis":
        st.pelvis_goal, st.pelvis_user = np.array(value, dtype=float), True
    elif part == "com":
        st.balance, st.com_drag = (float(value[0]), float(value[1])), None
    elif part == "head":
        st.head_target = np.array(value, dtype=float)
    elif part == "eyes":
        st.eyes_target = np.array(value, dtype=float)
    elif part.startswith("joint:"):
        j = loop.figure.joint(part[6:])
        j.displacement = np.clip(np.asarray(value, dtype=float)[:j.ndof], j.lower, j.upper)
