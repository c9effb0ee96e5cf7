"""The Peabody figure graph: environments, figures, segments, sites, joints and DOFs.

Book §2.2 (shared/spec/body-model.md §2). Units: metres and radians. Transforms are 4x4 column-vector
matrices (``p_parent = T @ p_local``).

Joint semantics. A joint connects ``from_site`` (on one segment) to ``to_site`` (on another); the
direction is part of the definition and never changes with rooting. Its displacement transform is
the product of its DOFs in ``type`` order, as Peabody wrote it with row vectors: ``type = A * B * C``
is ``D_row = A·B·C``, so in our column convention ``D = C @ B @ A``. Read as moving-frame rotations
from the from-site frame: the *last* listed DOF acts first (about the from-site's axis), then the one
before it about the moved axis, and so on. The to-site frame is ``W(to) = W(from) @ D``; with every
DOF at zero the two sites coincide.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from jackpy.errors import FigureError
from jackpy.peabody.geometry import Psurf
from jackpy.peabody.transforms import AXES, close, rotation, translation

if TYPE_CHECKING:
    from jackpy.peabody.groups import JointGroup
    from jackpy.peabody.kinematics import Kinematics

#: default limits of a DOF whose file gives none: a full turn for rotations, +-10 m for translations
DEFAULT_ROTATION_LIMITS = (-np.pi, np.pi)
DEFAULT_TRANSLATION_LIMITS = (-10.0, 10.0)


@dataclass
class Dof:
    """One degree of freedom: a rotation about (``kind='R'``) or translation along (``'T'``) a unit axis.

    ``lower``/``upper`` are radians for rotations, metres for translations.
    """

    kind: str
    axis: np.ndarray
    lower: float = -np.pi
    upper: float = np.pi

    def __post_init__(self) -> None:
        if self.kind not in ("R", "T"):
            raise FigureError(f"DOF kind must be 'R' or 'T', not {self.kind!r}")
        x, y, z = np.asarray(self.axis, dtype=float).reshape(3).tolist()
        big = max(abs(x), abs(y), abs(z))
        if not (math.isfinite(big) and big >= 1e-12):
            raise FigureError(f"DOF axis ({x:g}, {y:g}, {z:g}) has no direction")
        x, y, z = x / big, y / big, z / big  # (scaled first: the norm of a huge axis would overflow)
        n = math.sqrt(x * x + y * y + z * z)
        self.axis = np.array([x / n, y / n, z / n])

    @classmethod
    def about(cls, kind: str, axis: str, lower: float = -np.pi, upper: float = np.pi) -> Dof:
        """The DOF of ``kind`` about or along the named axis ``'x'``, ``'y'`` or ``'z'``: what
        ``Dof(kind, AXES[axis], lower, upper)`` gives, without the checks (a reader's fast path)."""
        dof = cls.__new__(cls)
        dof.kind, dof.axis, dof.lower, dof.upper = kind, AXES[axis].copy(), lower, upper
        return dof

    def transform(self, value: float) -> np.ndarray:
        """The 4x4 transform of this DOF at ``value``."""
        if self.kind == "R":
            return rotation(self.axis, value)
        return translation(*(self.axis * value))


@dataclass
class HumanMarker:
    """What makes a figure the standard human of ``jackpy.body`` (``human { ... }`` in a ``.fig``).

    ``population``, ``sex`` and ``percentile`` name the body; ``mass`` (kg), ``eye_drop`` (m),
    ``dims`` (dimension name -> metres) and ``overrides`` (name -> metres, kilograms for ``mass``)
    are its specification, so the body is restored exactly even if the population tables change.
    The peabody package only carries it; :mod:`jackpy.body.saved` turns it back into a body.
    """

    population: str
    sex: str
    percentile: float
    mass: float = 0.0
    eye_drop: float = 0.0
    dims: dict[str, float] = field(default_factory=dict)
    overrides: dict[str, float] = field(default_factory=dict)


@dataclass
class Site:
    """A named frame on a segment: ``location`` is its 4x4 transform in the segment's base frame."""

    name: str
    location: np.ndarray = field(default_factory=lambda: np.eye(4))


@dataclass
class Segment:
    """A rigid part: geometry, display attribute, sites and mass properties (segment frame, SI units)."""

    name: str
    psurf: Psurf | None = None
    attribute: str | None = None
    sites: dict[str, Site] = field(default_factory=dict)
    mass: float = 0.0
    com: np.ndarray = field(default_factory=lambda: np.zeros(3))
    inertia: np.ndarray = field(default_factory=lambda: np.zeros((3, 3)))

    def add_site(self, name: str, location: np.ndarray | None = None) -> Site:
        """Add (or replace) a site; returns it."""
        site = Site(name, np.eye(4) if location is None else np.asarray(location, dtype=float))
        self.sites[name] = site
        return site

    def site(self, name: str) -> Site:
        try:
            return self.sites[name]
        except KeyError:
            raise FigureError(f"segment {self.name!r} has no site {name!r}") from None


@dataclass
class Joint:
    """A joint from ``from_seg.from_site`` to ``to_seg.to_site`` with DOFs in ``type`` order."""

    name: str
    from_seg: str
    from_site: str
    to_seg: str
    to_site: str
    dofs: list[Dof] = field(default_factory=list)
    displacement: np.ndarray = field(default_factory=lambda: np.zeros(0))

    def __post_init__(self) -> None:
        d = np.asarray(self.displacement, dtype=float).reshape(-1)
        if d.size == 0:
            d = np.zeros(len(self.dofs))
        self.displacement = d

    @property
    def ndof(self) -> int:
        return len(self.dofs)

    @property
    def lower(self) -> np.ndarray:
        return np.array([d.lower for d in self.dofs])

    @property
    def upper(self) -> np.ndarray:
        return np.array([d.upper for d in self.dofs])

    def set_dof(self, k: int, value: float) -> float:
        """Set DOF ``k`` to ``value`` (rad or m) clamped to its limits; returns the value set."""
        d = self.dofs[k]
        disp = self.displacement.copy()
        disp[k] = float(np.clip(value, d.lower, d.upper))
        self.displacement = disp
        return float(disp[k])

    def transform(self, displacement: np.ndarray | None = None) -> np.ndarray:
        """Displacement transform ``D`` (to-site frame in from-site frame): ``D_n @ ... @ D_1``."""
        q = self.displacement if displacement is None else displacement
        out = np.eye(4)
        for dof, v in zip(self.dofs, q):
            out = dof.transform(v) @ out
        return out

    def type_text(self) -> str:
        """The joint type in Peabody notation, e.g. ``R(z) * R(1,0,0)``."""
        return " * ".join(f"{d.kind}({_axis_text(d.axis)})" for d in self.dofs)


def _axis_text(a: np.ndarray) -> str:
    for name, v in (("x", (1, 0, 0)), ("y", (0, 1, 0)), ("z", (0, 0, 1))):
        if close(a, v, 1e-12, rtol=1e-5):  # (np.allclose's default rtol)
            return name
    return ",".join(repr(float(x)) for x in a)


class Figure:
    """An articulated (or single-segment) object: segments joined by joints into a tree.

    ``root`` is the ``(segment, site)`` pair whose world frame is ``location``. The generalised
    coordinate vector ``q`` concatenates the joints' displacements in joint insertion order.
    """

    def __init__(self, name: str) -> None:
        self.name = name
        self.segments: dict[str, Segment] = {}
        self.joints: dict[str, Joint] = {}
        self.groups: dict[str, JointGroup] = {}
        self.root: tuple[str, str] | None = None
        self.location: np.ndarray = np.eye(4)
        #: set when the figure is a saved standard human (see :class:`HumanMarker`)
        self.human: HumanMarker | None = None
        self._kin: Kinematics | None = None
        self._topology_version = 0

    # ----- building -------------------------------------------------------------------------
    def add_segment(self, segment: Segment) -> Segment:
        if segment.name in self.segments:
            raise FigureError(f"figure {self.name!r}: duplicate segment {segment.name!r}")
        self.segments[segment.name] = segment
        self.topology_changed()
        return segment

    def add_joint(self, joint: Joint) -> Joint:
        if joint.name in self.joints:
            raise FigureError(f"figure {self.name!r}: duplicate joint {joint.name!r}")
        self.joints[joint.name] = joint
        self.topology_changed()
        return joint

    def add_group(self, group: "JointGroup") -> "JointGroup":
        if group.name in self.groups:
            raise FigureError(f"figure {self.name!r}: duplicate joint group {group.name!r}")
        for jn in group.joints:
            if jn not in self.joints:
                raise FigureError(f"figure {self.name!r}: group {group.name!r} names unknown joint {jn!r}")
            for other in self.groups.values():
                if jn in other.joints:
                    raise FigureError(f"figure {self.name!r}: joint {jn!r} is in groups "
                                      f"{other.name!r} and {group.name!r}")
        self.groups[group.name] = group
        group.apply(self)
        return group

    def topology_changed(self) -> None:
        """Drop the flattened-tree cache; call after adding/removing segments, joints or sites."""
        self._kin = None
        self._topology_version += 1

    # ----- access ---------------------------------------------------------------------------
    def segment(self, name: str) -> Segment:
        try:
            return self.segments[name]
        except KeyError:
            raise FigureError(f"figure {self.name!r} has no segment {name!r}") from None

    def joint(self, name: str) -> Joint:
        try:
            return self.joints[name]
        except KeyError:
            raise FigureError(f"figure {self.name!r} has no joint {name!r}") from None

    def site_location(self, seg: str, site: str) -> np.ndarray:
        return self.segment(seg).site(site).location

    def iter_sites(self) -> Iterator[tuple[str, Site]]:
        """Every site as ``("segment.site", Site)``."""
        for s in self.segments.values():
            for site in s.sites.values():
                yield f"{s.name}.{site.name}", site

    @property
    def ndof(self) -> int:
        return sum(j.ndof for j in self.joints.values())

    def dof_names(self) -> list[str]:
        """``joint[k]`` for every DOF in ``q`` order."""
        return [f"{j.name}[{k}]" for j in self.joints.values() for k in range(j.ndof)]

    def joint_dof_slice(self, name: str) -> slice:
        """The slice of ``q`` holding joint ``name``'s displacement."""
        start = 0
        for j in self.joints.values():
            if j.name == name:
                return slice(start, start + j.ndof)
            start += j.ndof
        raise FigureError(f"figure {self.name!r} has no joint {name!r}")

    @property
    def q(self) -> np.ndarray:
        """All joint displacements concatenated in joint order (radians / metres); a copy."""
        if not self.joints:
            return np.zeros(0)
        return np.concatenate([j.displacement for j in self.joints.values()])

    @q.setter
    def q(self, value: np.ndarray) -> None:
        # one private copy; each joint gets its own disjoint slice of it (one walk over the joints,
        # no per-joint copies: this runs once per IK solve, see docs/ik.md "Warm solves")
        v = np.array(value, dtype=float).reshape(-1)
        joints = list(self.joints.values())
        sizes = [len(j.dofs) for j in joints]
        if v.size != sum(sizes):
            raise FigureError(f"figure {self.name!r}: q has {v.size} values, figure has {sum(sizes)} DOFs")
        start = 0
        for j, n in zip(joints, sizes):
            j.displacement = v[start:start + n]
            start += n

    @property
    def lower(self) -> np.ndarray:
        return np.array([d.lower for j in self.joints.values() for d in j.dofs])

    @property
    def upper(self) -> np.ndarray:
        return np.array([d.upper for j in self.joints.values() for d in j.dofs])

    # ----- kinematics -----------------------------------------------------------------------
    def kinematics(self) -> "Kinematics":
        """The flattened rooted tree (cached; rebuilt when topology or root changes)."""
        if self._kin is None:
            from jackpy.peabody.kinematics import Kinematics

            self._kin = Kinematics(self)
        return self._kin

    def root_segment(self) -> str:
        if self.root is None:
            if not self.segments:
                raise FigureError(f"figure {self.name!r} has no segments")
            first = next(iter(self.segments.values()))
            return first.name
        return self.root[0]

    def root_site_location(self) -> np.ndarray:
        """Location of the root site in its segment (identity when no root site is set)."""
        if self.root is None:
            return np.eye(4)
        return self.site_location(*self.root)

    def world_transforms(self) -> dict[str, np.ndarray]:
        """World transform of every segment's base frame, by segment name."""
        kin = self.kinematics()
        fk = kin.forward(self.q, self.location)
        return {name: fk.segments[i] for i, name in enumerate(kin.segment_names)}

    def site_world(self, seg: str, site: str) -> np.ndarray:
        """World transform of ``seg.site`` at the current displacements."""
        kin = self.kinematics()
        fk = kin.forward(self.q, self.location)
        return fk.segments[kin.segment_index[seg]] @ self.site_location(seg, site)

    def reroot(self, seg: str, site: str) -> None:
        """Make ``seg.site`` the root without moving anything in the world (book §2.2.3)."""
        self.segment(seg).site(site)
        new_location = self.site_world(seg, site)
        self.root = (seg, site)
        self.location = new_location
        self._kin = None

    def centre_of_mass(self) -> np.ndarray:
        """World centre of mass (metres) at the current displacements."""
        kin = self.kinematics()
        return kin.centre_of_mass(kin.forward(self.q, self.location))

    @property
    def total_mass(self) -> float:
        return float(sum(s.mass for s in self.segments.values()))

    # ----- checks ---------------------------------------------------------------------------
    def validate(self, check_limits: bool = True) -> None:
        """Raise :class:`FigureError` naming the part at fault if the figure is not a valid tree.

        With ``check_limits`` every displacement must also lie within its DOF limits (files must
        satisfy this; kinematics only needs the structure and skips it).
        """
        for j in self.joints.values():
            for seg, site in ((j.from_seg, j.from_site), (j.to_seg, j.to_site)):
                if seg not in self.segments:
                    raise FigureError(f"figure {self.name!r}: joint {j.name!r} names unknown segment {seg!r}")
                if site not in self.segments[seg].sites:
                    raise FigureError(f"figure {self.name!r}: joint {j.name!r} names unknown site {seg}.{site}")
            if j.from_seg == j.to_seg:
                raise FigureError(f"figure {self.name!r}: joint {j.name!r} connects segment {j.from_seg!r} to itself")
            if j.displacement.size != j.ndof:
                raise FigureError(f"figure {self.name!r}: joint {j.name!r} has {j.displacement.size} "
                                  f"displacement values for a type with {j.ndof} DOFs")
            for k, (d, v) in enumerate(zip(j.dofs, j.displacement)):
                if d.lower > d.upper:
                    raise FigureError(f"figure {self.name!r}: joint {j.name!r} DOF {k}: lower limit above upper")
                if check_limits and not (d.lower - 1e-9 <= v <= d.upper + 1e-9):
                    unit, f = ("deg", 180 / np.pi) if d.kind == "R" else ("cm", 100.0)
                    raise FigureError(f"figure {self.name!r}: joint {j.name!r} DOF {k}: displacement "
                                      f"{v * f:.6g} {unit} outside limits [{d.lower * f:.6g}, {d.upper * f:.6g}] {unit}")
        if self.root is not None:
            seg, site = self.root
            if seg not in self.segments or site not in self.segments[seg].sites:
                raise FigureError(f"figure {self.name!r}: root names unknown site {seg}.{site}")
        self._check_tree()

    def _check_tree(self) -> None:
        if not self.segments:
            return
        parent = {s: s for s in self.segments}

        def find(s: str) -> str:
            while parent[s] != s:
                parent[s] = parent[parent[s]]
                s = parent[s]
            return s

        for j in self.joints.values():
            a, b = find(j.from_seg), find(j.to_seg)
            if a == b:
                raise FigureError(f"figure {self.name!r}: joint {j.name!r} closes a cycle between segments "
                                  f"{j.from_seg!r} and {j.to_seg!r} (Peabody figures are trees; close loops "
                                  "with IK constraints)")
            parent[a] = b
        start = find(self.root_segment())
        missing = [s for s in self.segments if find(s) != start]
        if missing:
            raise FigureError(f"figure {self.name!r}: segment {missing[0]!r} is not joined to the root "
                              f"segment {self.root_segment()!r}")


@dataclass
class Environment:
    """A world of figures (articulated or plain objects), by name, each placed by its ``location``.

    ``includes`` records the figure files an ``.env`` file included, for writing it back;
    ``outside`` the referenced files that lay outside the allowed folders (see
    :mod:`jackpy.peabody.paths`).
    """

    figures: dict[str, Figure] = field(default_factory=dict)
    includes: list[str] = field(default_factory=list)
    #: files read from outside the scene's folder and the library path (allowed explicitly)
    outside: list[str] = field(default_factory=list)

    def add(self, figure: Figure) -> Figure:
        if figure.name in self.figures:
            raise FigureError(f"environment already has a figure named {figure.name!r}")
        self.figures[figure.name] = figure
        return figure

    def figure(self, name: str) -> Figure:
        try:
            return self.figures[name]
        except KeyError:
            raise FigureError(f"environment has no figure {name!r}") from None
