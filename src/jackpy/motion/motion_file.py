"""The motion file ``NAME.motion.json`` (version 1; documented in docs/motion.md).

::

    {"jackpy_motion": 1,
     "timeline": {"figures": {...}, "motions": [...], "timed": [...], "keyframes": [...],
                  "duration": 10.0, "span": 3.0},
     "baked": {"fps": 30, "frames": N,
               "figures": {"NAME": {"human": "male:50", "dofs": ["left_hip.0", ...],
                                    "roots": ["right_foot.ball", ...],
                                    "root": [0, 0, 1, ...],                 # index into roots per frame
                                    "location": [[16 numbers row-major], ...],  # root-site world 4x4 per frame
                                    "q": [[ndof numbers], ...]}}}}         # displacements per frame

Everything is SI (metres, radians, seconds), y up. ``timeline`` is :meth:`Timeline.to_dict`;
``baked`` is optional and may exist without any motion (walking or creature generators, BVH
import): a player needs only ``dofs`` (joint name, dot, DOF index), ``q``, ``roots``/``root`` and
``location``. Reading checks everything: JSON syntax errors carry ``file:line:column``, wrong
values the key path (``motion.json: timeline.motions[2].side: expected one of left, right``).
Writing is atomic; numbers are written with ``repr`` precision, so a baked frame reads back to
the same bits.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from jackpy import jsonfile
from jackpy.atomic import atomic_write_text
from jackpy.errors import ParseError
from jackpy.motion.bake import Posture
from jackpy.motion.timeline import Timeline

if TYPE_CHECKING:
    from jackpy.peabody.model import Figure

FORMAT_VERSION = 1


@dataclass
class BakedFigure:
    """One figure's baked frames: DOF names, and per frame displacements, root and root location."""

    dofs: list[str]
    q: np.ndarray  # (N, ndof)
    roots: list[str]
    root: np.ndarray  # (N,) int
    location: np.ndarray  # (N, 4, 4)
    human: str | None = None

    @property
    def n_frames(self) -> int:
        return int(self.q.shape[0])

    @classmethod
    def from_postures(cls, figure: "Figure", postures: list[Posture], human: str | None = None) -> "BakedFigure":
        roots: list[str] = []
        idx = []
        for p in postures:
            r = ".".join(p.root) if p.root else ""
            if r not in roots:
                roots.append(r)
            idx.append(roots.index(r))
        return cls(dof_names(figure), np.array([p.q for p in postures]).reshape(len(postures), -1), roots,
                   np.array(idx, dtype=int), np.array([p.location for p in postures]).reshape(-1, 4, 4), human)

    def posture(self, figure: "Figure", i: int) -> Posture:
        """Frame ``i`` as a :class:`Posture` of ``figure`` (DOFs matched by name; others kept)."""
        names = dof_names(figure)
        q = figure.q
        index = {n: k for k, n in enumerate(names)}
        for k, n in enumerate(self.dofs):
            j = index.get(n)
            if j is not None:
                q[j] = self.q[i, k]
        r = self.roots[int(self.root[i])]
        return Posture(q, tuple(r.split(".", 1)) if r else None, self.location[i].copy())

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"dofs": self.dofs, "roots": self.roots, "root": self.root.tolist(),
                               "location": self.location.reshape(-1, 16).tolist(), "q": self.q.tolist()}
        if self.human:
            out = {"human": self.human, **out}
        return out


def dof_names(figure: "Figure") -> list[str]:
    """``joint.k`` for every DOF of ``figure`` in its q order."""
    return [f"{j.name}.{k}" for j in figure.joints.values() for k in range(j.ndof)]


@dataclass
class MotionFile:
    """A motion file's content: the timeline and, optionally, baked frames at ``fps``."""

    timeline: Timeline = field(default_factory=Timeline)
    fps: float | None = None
    baked: dict[str, BakedFigure] = field(default_factory=dict)

    @property
    def n_frames(self) -> int:
        return max((b.n_frames for b in self.baked.values()), default=0)

    @property
    def duration(self) -> float:
        """The baked span when frames exist (frames - 1) / fps, else the timeline's."""
        if self.baked and self.fps:
            return (self.n_frames - 1) / self.fps
        return self.timeline.duration

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"jackpy_motion": FORMAT_VERSION, "timeline": self.timeline.to_dict()}
        if self.baked:
            out["baked"] = {"fps": self.fps, "frames": self.n_frames,
                            "figures": {n: b.to_dict() for n, b in self.baked.items()}}
        return out


def save(mf: MotionFile, path: str | os.PathLike) -> None:
    """Write ``mf`` to ``path`` atomically (one line per baked frame array, compact elsewhere)."""
    atomic_write_text(Path(path), json.dumps(mf.to_dict(), separators=(",", ":")) + "\n")


def load(path: str | os.PathLike) -> MotionFile:
    """Read a motion file; :class:`ParseError` names the file and line:column or key path."""
    p = Path(path)
    file = str(p)
    try:
        data = jsonfile.load(p, ParseError)
    except FileNotFoundError:
        raise ParseError("no such motion file", file) from None
    except OSError as exc:
        raise ParseError(f"cannot read the motion file: {exc.strerror or exc}", file) from None
    try:
        return from_data(data)
    except jsonfile.Invalid as exc:
        raise jsonfile.schema_error(ParseError, file, exc) from None


def from_data(data: Any) -> MotionFile:
    """A :class:`MotionFile` from parsed JSON (raises :class:`jsonfile.Invalid`)."""
    data = jsonfile.obj(data, "")
    version = data.get("jackpy_motion")
    if version != FORMAT_VERSION:
        raise jsonfile.Invalid("jackpy_motion", f"expected {FORMAT_VERSION} (a jackpy motion file), found {version!r}")
    for k in data:
        if k not in ("jackpy_motion", "timeline", "baked"):
            raise jsonfile.Invalid(k, "unknown key (known: jackpy_motion, timeline, baked)")
    timeline = Timeline.from_dict(data.get("timeline", {}), "timeline")
    mf = MotionFile(timeline)
    if "baked" in data:
        bd = jsonfile.obj(data["baked"], "baked")
        mf.fps = jsonfile.num(jsonfile.required(bd, "fps", "baked"), "baked.fps", 1e-6)
        n = jsonfile.integer(jsonfile.required(bd, "frames", "baked"), "baked.frames", 0)
        for name, fd in jsonfile.obj(jsonfile.required(bd, "figures", "baked"), "baked.figures").items():
            mf.baked[name] = _baked_figure(fd, f"baked.figures.{name}", n)
    return mf


def _baked_figure(fd: Any, where: str, n: int) -> BakedFigure:
    fd = jsonfile.obj(fd, where)
    k = jsonfile.key
    dofs = [jsonfile.string(s, k(k(where, "dofs"), i)) for i, s in enumerate(jsonfile.arr(jsonfile.required(fd, "dofs", where), k(where, "dofs")))]
    roots = [jsonfile.string(s, k(k(where, "roots"), i)) for i, s in enumerate(jsonfile.arr(jsonfile.required(fd, "roots", where), k(where, "roots")))]
    q = _table(jsonfile.required(fd, "q", where), k(where, "q"), n, len(dofs))
    loc = _table(jsonfile.required(fd, "location", where), k(where, "location"), n, 16).reshape(n, 4, 4)
    rw = k(where, "root")
    ridx = jsonfile.arr(jsonfile.required(fd, "root", where), rw)
    if len(ridx) != n:
        raise jsonfile.Invalid(rw, f"expected {n} entries (one per frame), found {len(ridx)}")
    root = np.array([jsonfile.integer(r, k(rw, i), 0, max(0, len(roots) - 1)) for i, r in enumerate(ridx)], dtype=int)
    human = fd.get("human")
    if human is not None:
        human = jsonfile.string(human, k(where, "human"))
    return BakedFigure(dofs, q, roots, root, loc, human)


def _table(v: Any, where: str, rows: int, cols: int) -> np.ndarray:
    """A rows x cols list of lists of finite numbers."""
    v = jsonfile.arr(v, where)
    if len(v) != rows:
        raise jsonfile.Invalid(where, f"expected {rows} rows (one per frame), found {len(v)}")
    out = np.empty((rows, cols))
    for i, row in enumerate(v):
        rw = jsonfile.key(where, i)
        row = jsonfile.arr(row, rw)
        if len(row) != cols:
            raise jsonfile.Invalid(rw, f"expected {cols} numbers, found {len(row)}")
        try:
            out[i] = row
        except (TypeError, ValueError):
            for j, x in enumerate(row):
                jsonfile.num(x, jsonfile.key(rw, j))
            raise
        if not np.all(np.isfinite(out[i])) or any(isinstance(x, bool) for x in row):
            for j, x in enumerate(row):
                jsonfile.num(x, jsonfile.key(rw, j))
    return out
