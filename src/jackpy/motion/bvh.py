"""BVH motion capture files: reading (hierarchy, channels, frames), forward kinematics of every
joint per frame, and writing.

Reading follows the conventions the public files use (see ``shared/data/mocap/README.md``): each
joint's rotation channels compose in the order listed (``Zrotation Yrotation Xrotation`` is
R = Rz Ry Rx, intrinsic), degrees; a joint's position channels **replace** its OFFSET (Bandai's
constant per-joint positions would otherwise double every bone; for a root with offset 0 both
readings agree); any whitespace separates tokens (tabs, trailing spaces, ``Frames:<TAB>``);
numbers may be ``.0083333``, ``-0.0000`` or ``1.87e-05``. Errors are :class:`ParseError` with
``file:line:column``. Lengths stay in the file's units here (see :mod:`.retarget` for units).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np
from scipy.spatial.transform import Rotation

from jackpy.errors import ParseError

CHANNEL_NAMES = ("Xposition", "Yposition", "Zposition", "Xrotation", "Yrotation", "Zrotation")


@dataclass
class BVHJoint:
    """One joint: ``offset`` from its parent (file units), ``channels`` by name, ``end`` the End
    Site offset when it has one."""

    name: str
    parent: int
    offset: np.ndarray
    channels: list[str] = field(default_factory=list)
    end: np.ndarray | None = None
    first_channel: int = 0

    @property
    def rotation_order(self) -> str:
        """The rotation channels' axes in file order, e.g. ``"ZYX"``."""
        return "".join(c[0] for c in self.channels if c.endswith("rotation"))


@dataclass
class BVH:
    """A parsed file: joints in file order (parents first), frames (N, channels), frame time (s)."""

    joints: list[BVHJoint]
    frames: np.ndarray
    frame_time: float
    file: str = "<string>"

    @property
    def fps(self) -> float:
        return 1.0 / self.frame_time

    @property
    def names(self) -> list[str]:
        return [j.name for j in self.joints]

    def index(self, name: str) -> int:
        return self.names.index(name)

    def local(self, frames: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Per joint and frame the local rotation (N, J, 3, 3) and translation (N, J, 3)."""
        data = self.frames if frames is None else frames
        n, nj = data.shape[0], len(self.joints)
        rot = np.tile(np.eye(3), (n, nj, 1, 1))
        trans = np.tile(np.stack([j.offset for j in self.joints]), (n, 1, 1)).astype(float)
        for k, j in enumerate(self.joints):
            cols = {c: j.first_channel + i for i, c in enumerate(j.channels)}
            for axis, c in enumerate(("Xposition", "Yposition", "Zposition")):
                if c in cols:
                    trans[:, k, axis] = data[:, cols[c]]
            order = j.rotation_order
            if order:
                angles = np.stack([data[:, cols[f"{a}rotation"]] for a in order], axis=1)
                rot[:, k] = Rotation.from_euler(order.upper(), angles, degrees=True).as_matrix()
        return rot, trans

    def world(self, frames: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """World rotation (N, J, 3, 3) and position (N, J, 3) of every joint per frame."""
        rot, trans = self.local(frames)
        wr = np.empty_like(rot)
        wp = np.empty_like(trans)
        for k, j in enumerate(self.joints):
            if j.parent < 0:
                wr[:, k], wp[:, k] = rot[:, k], trans[:, k]
            else:
                p = j.parent
                wr[:, k] = wr[:, p] @ rot[:, k]
                wp[:, k] = wp[:, p] + np.einsum("nij,nj->ni", wr[:, p], trans[:, k])
        return wr, wp


_TOKEN = re.compile(r"\S+")


def parse(text: str, file: str = "<string>") -> BVH:
    """Parse BVH text; :class:`ParseError` with line and column at the first problem."""
    tokens: list[tuple[str, int, int]] = []
    lines = text.splitlines()
    motion_line = None
    for ln, line in enumerate(lines, 1):
        for m in _TOKEN.finditer(line):
            tokens.append((m.group(), ln, m.start() + 1))
            if m.group() == "MOTION" and motion_line is None:
                motion_line = ln
                break
        if motion_line is not None:
            break
    pos = 0

    def err(msg: str, tok: tuple[str, int, int] | None = None) -> ParseError:
        if tok is None:
            tok = tokens[pos] if pos < len(tokens) else ("", len(lines), 1)
        return ParseError(msg, file, tok[1], tok[2])

    def take(expected: str | None = None) -> tuple[str, int, int]:
        nonlocal pos
        if pos >= len(tokens):
            raise err(f"expected {expected or 'more'}, found the end of the file")
        tok = tokens[pos]
        if expected is not None and tok[0] != expected:
            raise err(f"expected {expected!r}, found {tok[0]!r}", tok)
        pos += 1
        return tok

    def number() -> float:
        tok = take()
        try:
            v = float(tok[0])
        except ValueError:
            raise err(f"expected a number, found {tok[0]!r}", tok) from None
        if not math.isfinite(v):
            raise err(f"expected a finite number, found {tok[0]!r}", tok)
        return v

    take("HIERARCHY")
    joints: list[BVHJoint] = []
    n_channels = 0

    def joint(parent: int, depth: int) -> None:
        nonlocal n_channels
        if depth > 200:
            raise err("hierarchy nested too deeply")
        name = take()[0]
        k = len(joints)
        take("{")
        take("OFFSET")
        offset = np.array([number(), number(), number()])
        j = BVHJoint(name, parent, offset, first_channel=n_channels)
        joints.append(j)
        if pos < len(tokens) and tokens[pos][0] == "CHANNELS":
            take()
            tok = take()
            try:
                count = int(tok[0])
            except ValueError:
                raise err(f"expected a channel count, found {tok[0]!r}", tok) from None
            if not 0 <= count <= 6:
                raise err(f"a joint has 0 to 6 channels, not {count}", tok)
            for _ in range(count):
                c = take()
                if c[0] not in CHANNEL_NAMES:
                    raise err(f"unknown channel {c[0]!r} (one of {', '.join(CHANNEL_NAMES)})", c)
                if c[0] in j.channels:
                    raise err(f"channel {c[0]!r} given twice", c)
                j.channels.append(c[0])
            n_channels += count
        while True:
            tok = take()
            if tok[0] == "}":
                return
            if tok[0] == "JOINT":
                joint(k, depth + 1)
            elif tok[0] == "End":
                take("Site")
                take("{")
                take("OFFSET")
                j.end = np.array([number(), number(), number()])
                take("}")
            else:
                raise err(f"expected JOINT, End Site or '}}', found {tok[0]!r}", tok)

    take("ROOT")
    joint(-1, 0)
    if pos < len(tokens):
        tok = tokens[pos]
        if tok[0] == "ROOT":
            raise err("only one ROOT is supported", tok)
        if tok[0] != "MOTION":
            raise err(f"expected MOTION, found {tok[0]!r}", tok)
    if motion_line is None:
        raise err("expected MOTION, found the end of the file")
    # MOTION section: Frames: N, Frame Time: T, then N rows of n_channels numbers
    rest = lines[motion_line:]

    def header(i: int, label: str) -> str:
        if i >= len(rest):
            raise ParseError(f"expected '{label}', found the end of the file", file, motion_line + i + 1, 1)
        line = rest[i]
        if not line.strip().startswith(label):
            col = len(line) - len(line.lstrip()) + 1
            raise ParseError(f"expected '{label}'", file, motion_line + i + 1, col)
        return line.strip()[len(label):].strip()

    ftext = header(0, "Frames:")
    try:
        n_frames = int(ftext)
    except ValueError:
        raise ParseError(f"expected a frame count, found {ftext!r}", file, motion_line + 1, 1) from None
    ttext = header(1, "Frame Time:")
    try:
        frame_time = float(ttext)
    except ValueError:
        raise ParseError(f"expected a frame time, found {ttext!r}", file, motion_line + 2, 1) from None
    if n_frames < 1:
        raise ParseError(f"a motion needs at least 1 frame, not {n_frames}", file, motion_line + 1, 1)
    if not (math.isfinite(frame_time) and frame_time > 0):
        raise ParseError(f"frame time must be > 0 s, not {ttext}", file, motion_line + 2, 1)
    rows = [r for r in rest[2:] if r.strip()]
    if len(rows) < n_frames:
        raise ParseError(f"expected {n_frames} frames, found {len(rows)}", file, motion_line + 2 + len(rows), 1)
    data = np.empty((n_frames, n_channels))
    line_no = motion_line + 3
    k = 0
    for r in rest[2:]:
        if k >= n_frames:
            break
        if r.strip():
            parts = r.split()
            if len(parts) != n_channels:
                raise ParseError(f"expected {n_channels} numbers in a frame, found {len(parts)}", file, line_no, 1)
            try:
                data[k] = [float(x) for x in parts]
            except ValueError:
                bad = next(x for x in parts if not _is_float(x))
                raise ParseError(f"expected a number, found {bad!r}", file, line_no, r.find(bad) + 1) from None
            if not np.all(np.isfinite(data[k])):
                raise ParseError("expected finite numbers", file, line_no, 1)
            k += 1
        line_no += 1
    return BVH(joints, data, frame_time, file)


def _is_float(x: str) -> bool:
    try:
        float(x)
        return True
    except ValueError:
        return False


def read(path: str) -> BVH:
    """Read a BVH file (UTF-8 or Latin-1 text)."""
    from pathlib import Path

    raw = Path(path).read_bytes()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
    return parse(text, str(path))


def format_bvh(joints: list[BVHJoint], frames: np.ndarray, frame_time: float) -> str:
    """BVH text of ``joints`` (parents first) and ``frames`` (N, channels); numbers in repr form."""
    children: dict[int, list[int]] = {}
    for k, j in enumerate(joints):
        children.setdefault(j.parent, []).append(k)
    out = ["HIERARCHY"]

    def emit(k: int, depth: int) -> None:
        j = joints[k]
        ind = "\t" * depth
        out.append(f"{ind}{'ROOT' if j.parent < 0 else 'JOINT'} {j.name}")
        out.append(f"{ind}{{")
        out.append(f"{ind}\tOFFSET {' '.join(repr(float(v)) for v in j.offset)}")
        out.append(f"{ind}\tCHANNELS {len(j.channels)} {' '.join(j.channels)}")
        for c in children.get(k, []):
            emit(c, depth + 1)
        if j.end is not None:
            out.append(f"{ind}\tEnd Site")
            out.append(f"{ind}\t{{")
            out.append(f"{ind}\t\tOFFSET {' '.join(repr(float(v)) for v in j.end)}")
            out.append(f"{ind}\t}}")
        out.append(f"{ind}}}")

    emit(children[-1][0], 0)
    out.append("MOTION")
    out.append(f"Frames: {frames.shape[0]}")
    out.append(f"Frame Time: {frame_time!r}")
    for row in frames:
        out.append(" ".join(repr(float(v)) for v in row))
    return "\n".join(out) + "\n"
