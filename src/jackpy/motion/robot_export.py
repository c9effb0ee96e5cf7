"""URDF and MJCF export of a figure's kinematic tree: links/bodies, joints with axes and limits,
sites as frames, masses and inertias from the body model.

Both formats describe the same tree, rooted where the figure is rooted. Each segment ``s`` becomes
one body (MJCF) or link (URDF) whose frame is ``W(s) @ O_s``, where ``O_s`` is the location of the
site through which ``s`` hangs from its parent (the joint's site on ``s``; identity for the root).
So a body's frame is its incoming joint's frame and every joint sits at its body's origin.

Joint semantics (see :mod:`jackpy.peabody.model`): a joint's displacement is ``D = T_n ... T_1``
(moving frames: ``T_n`` acts first, about the from-site's axis). Traversed *down* (from-site on the
parent) the body is ``W(p) L(from) T_n ... T_1``; traversed *up* it is ``W(p) L(to) T_1^-1 ... T_n^-1``.
MJCF applies a body's joints in document order in moving frames, so a down joint lists its DOFs
``n .. 1`` with their axes, an up joint ``1 .. n`` with negated axes; the MJCF/URDF joint value is
always jackpy's displacement. URDF joints have one DOF each: a joint of ``k > 1`` DOFs becomes a
chain of ``k`` joints through ``k - 1`` massless links named ``JOINT.dof<i>``.

Names: a DOF's joint is called ``JOINT`` when the jackpy joint has one DOF, else ``JOINT.<i>``
(``i`` the DOF's index in the joint, 0-based). Sites are MJCF ``<site name="SEGMENT.SITE">`` and URDF
massless links ``SEGMENT.SITE`` on fixed joints. The URDF has a ``world`` link fixed at the figure's
location; the MJCF root body is placed there, with a ``<freejoint name="root">`` when
``floating=True``. ``frozen`` joints are welded at their current displacement (no joint written).

Masses: each segment's mass, centre of mass and inertia about it (kg, m, kg m^2) in the body frame;
MJCF ``fullinertia``, URDF ``<inertia>`` with the origin at the centre of mass. Segments without
mass (e.g. the shoulder frames) get MuJoCo's ``boundmass``/``boundinertia`` floor (1e-6 kg,
1e-10 kg m^2) so that every moving body is valid; the URDF omits their ``<inertial>``. No geometry
is exported (the psurf meshes stay jackpy's). Units: metres, radians, kilograms.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable
from dataclasses import dataclass, field
from xml.sax.saxutils import quoteattr

import numpy as np

from jackpy.atomic import atomic_write_text
from jackpy.errors import FigureError
from jackpy.peabody.model import Figure
from jackpy.peabody.transforms import rigid_inverse

#: effort (N m or N) and velocity (rad/s or m/s) written on URDF joints, which require them;
#: jackpy has no actuator model, so these are nominal
URDF_EFFORT, URDF_VELOCITY = 1000.0, 10.0


@dataclass
class DofOut:
    """One exported single-DOF joint: name, ``"R"``/``"T"``, axis in its frame, limits (rad/m)."""

    name: str
    kind: str
    axis: np.ndarray
    lower: float
    upper: float


@dataclass
class BodyOut:
    """One segment as a body: its parent, placement in the parent body at zero, DOFs in order."""

    segment: str
    parent: str | None
    placement: np.ndarray  # parent body frame (world for the root) -> this body's frame at zero
    offset: np.ndarray  # O_s: body frame = W(s) @ O_s
    dofs: list[DofOut] = field(default_factory=list)
    joint: str | None = None


def kinematic_tree(figure: Figure, frozen: Iterable[str] = ()) -> list[BodyOut]:
    """The figure's bodies in breadth-first order from the root (see the module docstring)."""
    figure.validate(check_limits=False)
    frozen = set(frozen)
    for name in frozen:
        figure.joint(name)
    root = figure.root_segment()
    loc_root = figure.root_site_location()
    bodies = [BodyOut(root, None, figure.location @ rigid_inverse(loc_root), np.eye(4))]
    offsets = {root: np.eye(4)}
    seen = {root}
    queue = [root]
    while queue:
        seg = queue.pop(0)
        for j in figure.joints.values():
            if seg not in (j.from_seg, j.to_seg) or {j.from_seg, j.to_seg} <= seen:
                continue
            down = j.from_seg == seg
            child = j.to_seg if down else j.from_seg
            near = figure.site_location(seg, j.from_site if down else j.to_site)
            far = figure.site_location(child, j.to_site if down else j.from_site)
            placement = rigid_inverse(offsets[seg]) @ near
            names = [j.name] if j.ndof == 1 else [f"{j.name}.{k}" for k in range(j.ndof)]
            order = range(j.ndof - 1, -1, -1) if down else range(j.ndof)
            dofs = [DofOut(names[k], j.dofs[k].kind, j.dofs[k].axis * (1.0 if down else -1.0),
                           j.dofs[k].lower, j.dofs[k].upper) for k in order]
            if j.name in frozen:
                D = j.transform()
                placement = placement @ (D if down else rigid_inverse(D))
                dofs = []
            bodies.append(BodyOut(child, seg, placement, far, dofs, j.name))
            offsets[child] = far
            seen.add(child)
            queue.append(child)
    return bodies


# ----- number formatting -----------------------------------------------------------------------
def _f(x: float) -> str:
    """Shortest round-trip text of a float (``-0`` as ``0``)."""
    x = float(x)
    return "0" if x == 0.0 else repr(x)


def _v(v: Iterable[float]) -> str:
    return " ".join(_f(x) for x in v)


def _quat(R: np.ndarray) -> np.ndarray:
    """Unit quaternion (w, x, y, z) of a rotation matrix (Shepperd's method, sign with w >= 0)."""
    t = np.trace(R)
    if t > 0:
        s = math.sqrt(t + 1.0) * 2
        q = np.array([0.25 * s, (R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s, (R[1, 0] - R[0, 1]) / s])
    else:
        i = int(np.argmax(np.diag(R)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = math.sqrt(1.0 + R[i, i] - R[j, j] - R[k, k]) * 2
        q = np.zeros(4)
        q[0] = (R[k, j] - R[j, k]) / s
        q[1 + i] = 0.25 * s
        q[1 + j] = (R[j, i] + R[i, j]) / s
        q[1 + k] = (R[k, i] + R[i, k]) / s
    q /= np.linalg.norm(q)
    return -q if q[0] < 0 else q


def _rpy(R: np.ndarray) -> np.ndarray:
    """URDF roll, pitch, yaw with ``R = Rz(yaw) Ry(pitch) Rx(roll)``."""
    pitch = math.atan2(-R[2, 0], math.hypot(R[0, 0], R[1, 0]))
    if math.hypot(R[0, 0], R[1, 0]) < 1e-12:  # gimbal lock: put everything in roll
        return np.array([math.atan2(-R[1, 2], R[1, 1]), pitch, 0.0])
    return np.array([math.atan2(R[2, 1], R[2, 2]), pitch, math.atan2(R[1, 0], R[0, 0])])


def _mass(figure: Figure, body: BodyOut) -> tuple[float, np.ndarray, np.ndarray]:
    """(mass, centre of mass, inertia about it) of ``body``'s segment in the body frame."""
    seg = figure.segment(body.segment)
    inv = rigid_inverse(body.offset)
    R = inv[:3, :3]
    return float(seg.mass), inv[:3, :3] @ seg.com + inv[:3, 3], R @ np.asarray(seg.inertia) @ R.T


# ----- MJCF --------------------------------------------------------------------------------------
def to_mjcf(figure: Figure, *, floating: bool = False, frozen: Iterable[str] = ()) -> str:
    """MJCF (MuJoCo XML) text of the figure's kinematic tree."""
    bodies = kinematic_tree(figure, frozen)
    children: dict[str | None, list[BodyOut]] = {}
    for b in bodies:
        children.setdefault(b.parent, []).append(b)
    out = [f"<mujoco model={quoteattr(figure.name)}>",
           '  <compiler angle="radian" autolimits="false" inertiafromgeom="false" '
           'boundmass="1e-06" boundinertia="1e-10"/>',
           "  <worldbody>"]

    def emit(b: BodyOut, depth: int) -> None:
        ind = "  " * depth
        p = b.placement
        out.append(f'{ind}<body name={quoteattr(b.segment)} pos="{_v(p[:3, 3])}" quat="{_v(_quat(p[:3, :3]))}">')
        if b.parent is None and floating:
            out.append(f'{ind}  <freejoint name="root"/>')
        m, c, inertia = _mass(figure, b)
        if m > 0:
            six = (inertia[0, 0], inertia[1, 1], inertia[2, 2], inertia[0, 1], inertia[0, 2], inertia[1, 2])
            out.append(f'{ind}  <inertial pos="{_v(c)}" mass="{_f(m)}" fullinertia="{_v(six)}"/>')
        for d in b.dofs:
            kind = "hinge" if d.kind == "R" else "slide"
            out.append(f'{ind}  <joint name={quoteattr(d.name)} type="{kind}" pos="0 0 0" axis="{_v(d.axis)}" '
                       f'limited="true" range="{_f(d.lower)} {_f(d.upper)}"/>')
        inv = rigid_inverse(b.offset)
        for site in figure.segment(b.segment).sites.values():
            T = inv @ site.location
            out.append(f'{ind}  <site name={quoteattr(b.segment + "." + site.name)} pos="{_v(T[:3, 3])}" '
                       f'quat="{_v(_quat(T[:3, :3]))}"/>')
        for c in children.get(b.segment, []):
            emit(c, depth + 1)
        out.append(f"{ind}</body>")

    emit(bodies[0], 2)
    out += ["  </worldbody>", "</mujoco>", ""]
    return "\n".join(out)


# ----- URDF ----------------------------------------------------------------------------------------
def to_urdf(figure: Figure, *, frozen: Iterable[str] = ()) -> str:
    """URDF text of the figure's kinematic tree (a ``world`` link fixed at the figure's location)."""
    bodies = kinematic_tree(figure, frozen)
    out = ['<?xml version="1.0"?>', f"<robot name={quoteattr(figure.name)}>", '  <link name="world"/>']
    links = {"world"} | {b.segment for b in bodies}

    def origin(T: np.ndarray) -> str:
        return f'<origin xyz="{_v(T[:3, 3])}" rpy="{_v(_rpy(T[:3, :3]))}"/>'

    def link(name: str, inertial: str = "") -> None:
        out.append(f"  <link name={quoteattr(name)}>{inertial}</link>" if inertial else
                   f"  <link name={quoteattr(name)}/>")

    def joint(name: str, kind: str, parent: str, child: str, T: np.ndarray, d: DofOut | None = None) -> None:
        body = [f"    {origin(T)}", f"    <parent link={quoteattr(parent)}/>", f"    <child link={quoteattr(child)}/>"]
        if d is not None:
            body += [f'    <axis xyz="{_v(d.axis)}"/>',
                     f'    <limit lower="{_f(d.lower)}" upper="{_f(d.upper)}" effort="{_f(URDF_EFFORT)}" '
                     f'velocity="{_f(URDF_VELOCITY)}"/>']
        out.append(f"  <joint name={quoteattr(name)} type=\"{kind}\">")
        out.extend(body)
        out.append("  </joint>")

    for b in bodies:
        m, c, inertia = _mass(figure, b)
        inertial = ""
        if m > 0:
            inertial = (f'<inertial><origin xyz="{_v(c)}" rpy="0 0 0"/><mass value="{_f(m)}"/>'
                        f'<inertia ixx="{_f(inertia[0, 0])}" ixy="{_f(inertia[0, 1])}" ixz="{_f(inertia[0, 2])}" '
                        f'iyy="{_f(inertia[1, 1])}" iyz="{_f(inertia[1, 2])}" izz="{_f(inertia[2, 2])}"/></inertial>')
        link(b.segment, inertial)
        parent = "world" if b.parent is None else b.parent
        if not b.dofs:
            joint(b.joint or f"world_to_{b.segment}", "fixed", parent, b.segment, b.placement)
        for k, d in enumerate(b.dofs):
            last = k == len(b.dofs) - 1
            child = b.segment if last else f"{b.joint}.dof{k}"
            if not last:
                if child in links:
                    raise FigureError(f"figure {figure.name!r}: link name {child!r} is taken")
                links.add(child)
                link(child)
            joint(d.name, "revolute" if d.kind == "R" else "prismatic", parent, child,
                  b.placement if k == 0 else np.eye(4), d)
            parent = child
        inv = rigid_inverse(b.offset)
        for site in figure.segment(b.segment).sites.values():
            name = f"{b.segment}.{site.name}"
            if name in links:
                raise FigureError(f"figure {figure.name!r}: link name {name!r} is taken")
            links.add(name)
            link(name)
            joint(f"{name}.frame", "fixed", b.segment, name, inv @ site.location)
    out += ["</robot>", ""]
    return "\n".join(out)


def joint_values(figure: Figure, frozen: Iterable[str] = ()) -> dict[str, float]:
    """The exported joints' values at the figure's current displacements, by exported name."""
    frozen = set(frozen)
    out = {}
    for j in figure.joints.values():
        if j.name in frozen:
            continue
        for k, v in enumerate(j.displacement):
            out[j.name if j.ndof == 1 else f"{j.name}.{k}"] = float(v)
    return out


def export(figure: Figure, path: str | os.PathLike[str], *, floating: bool = False,
           frozen: Iterable[str] = ()) -> str:
    """Write ``figure`` as URDF (``.urdf``) or MJCF (``.xml``/``.mjcf``) atomically; returns the format."""
    suffix = os.fspath(path).lower().rsplit(".", 1)[-1]
    if suffix == "urdf":
        if floating:
            raise FigureError("URDF has no floating joint: export the MJCF (.xml) for a floating root")
        atomic_write_text(path, to_urdf(figure, frozen=frozen))
        return "urdf"
    if suffix in ("xml", "mjcf"):
        atomic_write_text(path, to_mjcf(figure, floating=floating, frozen=frozen))
        return "mjcf"
    raise FigureError(f"{os.fspath(path)}: unknown export format (use .urdf, or .xml / .mjcf for MJCF)")
