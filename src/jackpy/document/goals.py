"""The user's goals as the document holds them: an IK goal of a registered kind on a figure's site,
with the operator's manipulation frame, switch and priority.

The :class:`~jackpy.ik.goals.Goal` object inside a :class:`GoalEntry` owns the targets; the
behavior loop is handed that same object (:meth:`~jackpy.behaviors.BehaviorLoop.add_user_goal`)
and reads them, so nothing is copied back and forth. The operator drives ``manip`` (its
manipulation transform ``M``); the target frame is ``M`` with rotation ``R_M @ offset`` (spec
§2.10), and every change of it is passed one way into the goal by ``goal.set_frame``.

A goal with ``role == "eyes"`` is the gaze behavior's look-at point: an :class:`~jackpy.ik.goals.Aim`
of the view site at the point, handed to the gaze (``manipulation.move_eyes``), not to IK.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from jackpy.errors import SessionError
from jackpy.ik.goals import GOAL_TYPES, Aim, Orientation, Position, PositionOrientation, SiteGoal
from jackpy.ik.goals.base import Goal
from jackpy.peabody import Figure

EYES = "eyes"
"""The role (and the shown kind) of the gaze's look-at point."""

FRAME_TYPES = (Position, Orientation, PositionOrientation)
"""Goal types that bring a site onto a frame: on a human's hand, foot, pelvis or head they are the
operator's effector goals, passed to the behaviors as Jack's manipulation commands."""


def placeable_kinds() -> list[str]:
    """Kinds of goal a user can put on a site (every registered :class:`SiteGoal` kind with a
    :meth:`~jackpy.ik.goals.SiteGoal.set_frame`), in registration order."""
    return [k for k, cls in GOAL_TYPES.items()
            if issubclass(cls, SiteGoal) and cls.set_frame is not SiteGoal.set_frame]


@dataclass(eq=False)
class GoalEntry:
    """A goal of the document: ``goal`` (its kind, site, chain, weight and targets) on ``figure``."""

    key: str
    figure: str
    goal: SiteGoal
    enabled: bool = True
    priority: int = 0
    manip: np.ndarray = field(default_factory=lambda: np.eye(4))
    offset: np.ndarray = field(default_factory=lambda: np.eye(3))
    role: str | None = None

    @property
    def kind(self) -> str:
        return EYES if self.role == EYES else self.goal.kind

    @property
    def site(self) -> str:
        return self.goal.site_name

    @property
    def chain(self) -> str | None:
        return self.goal.chain  # type: ignore[return-value]

    @chain.setter
    def chain(self, value: str | None) -> None:
        self.goal.chain = value or None

    @property
    def weight(self) -> float:
        return self.goal.weight

    @weight.setter
    def weight(self, value: float) -> None:
        self.goal.weight = max(0.0, float(value))

    @property
    def target(self) -> np.ndarray:
        """The target frame (world 4x4, a copy): ``manip`` with rotation ``R_M @ offset``."""
        t = np.array(self.manip, dtype=float)
        t[:3, :3] = self.manip[:3, :3] @ self.offset
        return t

    @target.setter
    def target(self, frame: np.ndarray) -> None:
        """Put the target frame at ``frame``: the manipulation frame moves to its origin and keeps
        its rotation (the offset takes the rest)."""
        f = np.asarray(frame, dtype=float)
        self.manip = np.array(self.manip, dtype=float)
        self.manip[:3, 3] = f[:3, 3]
        self.offset = self.manip[:3, :3].T @ f[:3, :3]
        self.goal.set_frame(self.target)

    def move(self, manip: np.ndarray) -> None:
        """The operator moved the manipulation frame to ``manip``; the targets follow."""
        self.manip = np.array(manip, dtype=float)
        self.goal.set_frame(self.target)

    def marker_position(self) -> np.ndarray:
        """Where the goal marker is drawn (m)."""
        return self.manip[:3, 3].copy()

    # ----- files ------------------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        return {"key": self.key, "figure": self.figure, "role": self.role, "enabled": self.enabled,
                "priority": self.priority, "manip": _m(self.manip), "offset": _m(self.offset),
                "goal": self.goal.to_dict()}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> GoalEntry:
        """An entry of :meth:`to_dict`, or of the version-1 sidecar (``kind``, ``target``, ``axis``)."""
        if "goal" not in d:
            return _from_v1(d)
        goal = Goal.from_dict(d["goal"])
        if not isinstance(goal, SiteGoal):
            raise SessionError(f"goal {d['key']!r}: a {goal.kind} goal is not on a site")
        return cls(d["key"], d["figure"], goal, bool(d["enabled"]), int(d["priority"]),
                   np.asarray(d["manip"], float).reshape(4, 4), np.asarray(d["offset"], float).reshape(3, 3),
                   d.get("role"))


def new_goal(fig: Figure, site: str, kind: str, key: str | None = None, **params: Any) -> GoalEntry:
    """A goal of registered ``kind`` on ``fig``'s ``site`` that holds at the current posture (at
    the kind's :meth:`~jackpy.ik.goals.SiteGoal.placement` of the site's frame)."""
    cls = GOAL_TYPES.get(kind)
    if cls is None or not issubclass(cls, SiteGoal):
        raise ValueError(f"goal kind must be one of {', '.join(placeable_kinds())}, not {kind!r}")
    key = key or f"{fig.name}:{site}"
    frame = cls.placement(fig.site_world(*site.split(".", 1)), params)
    manip = np.eye(4)
    manip[:3, 3] = frame[:3, 3]
    goal = cls.at_frame(site, frame, name=key, **params)
    return GoalEntry(key, fig.name, goal, manip=manip, offset=frame[:3, :3].copy())


def eyes_goal(fig: Figure, view_site: str, point: np.ndarray) -> GoalEntry:
    """The gaze's look-at point ``point`` (world, m) of human ``fig`` (key ``FIGURE:eyes``)."""
    manip = np.eye(4)
    manip[:3, 3] = point
    key = f"{fig.name}:{EYES}"
    return GoalEntry(key, fig.name, Aim(view_site, point, name=key), manip=manip, role=EYES)


def _m(a: np.ndarray) -> list[float]:
    return [float(x) for x in np.asarray(a, float).reshape(-1)]


def _from_v1(d: dict[str, Any]) -> GoalEntry:
    """A goal of a version-1 sidecar: ``kind`` among the then built-in kinds, the target frame,
    and for ``aim`` the site axis, for ``plane``/``half-space`` the normal in the target frame."""
    kind, key = d["kind"], d["key"]
    manip = np.asarray(d["manip"], float).reshape(4, 4)
    offset = np.asarray(d["offset"], float).reshape(3, 3)
    axis = np.asarray(d.get("axis", [0.0, 0.0, 1.0]), float).reshape(3)
    chain = d.get("chain") or None
    if kind == EYES:
        target = np.asarray(d["target"], float).reshape(4, 4)
        e = GoalEntry(key, d["figure"], Aim(d["site"], target[:3, 3], name=key), bool(d["enabled"]),
                      int(d["priority"]), manip, offset, EYES)
        return e
    cls = GOAL_TYPES.get(kind)
    if cls is None or not issubclass(cls, SiteGoal):
        raise SessionError(f"goal {key!r}: unknown goal kind {kind!r}")
    params: dict[str, Any] = {}
    if kind == "aim":
        params["axis"] = axis
    elif kind in ("plane", "half-space"):
        offset = offset @ _rotation_y_to(axis)  # the normal is the target frame's y axis now
    e = GoalEntry(key, d["figure"], None, bool(d["enabled"]), int(d["priority"]), manip, offset)  # type: ignore[arg-type]
    e.goal = cls.at_frame(d["site"], e.target, chain, float(d["weight"]), key, **params)
    return e


def _rotation_y_to(axis: np.ndarray) -> np.ndarray:
    """A rotation taking +y to the unit direction of ``axis``."""
    y = np.array([0.0, 1.0, 0.0])
    a = axis / np.linalg.norm(axis)
    v, c = np.cross(y, a), float(y @ a)
    if np.linalg.norm(v) < 1e-12:
        return np.eye(3) if c > 0 else np.diag([1.0, -1.0, -1.0])
    k = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + k + k @ k / (1.0 + c)
