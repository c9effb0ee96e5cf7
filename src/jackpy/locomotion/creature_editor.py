"""The creature editor's model (Sims Ch. 4, App. A): a 2-D drawing of nodes and links on the
"dissection table", its editing operations with undo, the network analysis that finds body, head,
tail and legs, and the 3-D Peabody figure built from it.

**Drawing frame.** Editor coordinates ``(x, y)`` in drawing units (``units``: cm by default),
screen convention: ``x`` right, ``y`` down, the head towards ``-y`` (up the screen). The creature
is seen from above. **Mapping to the figure** (eq. 4.1, turned so the head is jackpy's forward
``+z``): ``x_world = -x * unit``, ``y_world = 0``, ``z_world = -y * unit``, so the screen's left
(``x < 0``) is the creature's left (``+x``). The figure is built flat in the horizontal plane,
then stood up by its default posture (below); its root is ``body.centre`` ``body_height`` above
the floor with its feet on it.

**Network analysis (4.2).** The largest connected component only; appendage tips are nodes of
degree 1; from a tip walk inward while nodes have degree 2: the first node of degree > 2 is the
appendage's base. Our rule for head and tail (a gap in the thesis): an appendage whose base is the
body's front-most node (least ``y``) and whose tip lies ahead of it within 30 degrees of straight
ahead is the head; the same at the back (greatest ``y``, pointing back) is the tail; every other
appendage is a leg. The body is all base nodes plus every node in no appendage: one rigid link.

**Axes (2.4).** Every leg base gets a ball joint of two axes. *Insect*: the outer axis vertical
(yaw), the inner and every knee axis horizontal, perpendicular to the leg
(``normalize(up x (d1 + d2))``), so the leg bends in its own vertical plane. *Mammal*: the outer
axis is that horizontal one (it folds the leg down under the body), the inner and the knees are
vertical in the creation pose, so after folding they flex fore and aft. Head and tail joints are
single horizontal axes.

**Default posture.** Insect: each leg's first link rises 30 degrees, its last link points 75
degrees down, links between in proportion; mammal: the leg folds 80 degrees down, its first link
swings 35 degrees and each knee bends 70 degrees, alternately back and forward. The posture is
written as the joints' displacements, so the figure stands in its file; walking uses it as the
neutral stance.
"""

from __future__ import annotations

import copy
import json
import math
import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from jackpy.errors import FigureError, ParseError
from jackpy.peabody.geometry import Mesh, Psurf
from jackpy.peabody.model import Dof, Figure, Joint, Segment

STYLES = ("insect", "mammal")
UNITS = {"cm": 0.01, "mm": 0.001, "m": 1.0}
BOX_PSURF = "creature_box.pss"
#: snapping distance (drawing units) of new nodes onto the figure axes
SNAP = 1.0


def wrap(a: float) -> float:
    """An angle wrapped into (-pi, pi]."""
    a = math.fmod(a + math.pi, 2 * math.pi)
    if a <= 0:
        a += 2 * math.pi
    return a - math.pi


def inside_lasso(point: Sequence[float], polygon: Sequence[Sequence[float]]) -> bool:
    """Winding-angle test (App. A.2, with each difference wrapped to (-pi, pi]): the point is inside
    if the summed angle is +-2 pi. The polygon may be concave, of either orientation; its first
    point need not be repeated."""
    px, py = float(point[0]), float(point[1])
    pts = [tuple(map(float, p)) for p in polygon]
    if len(pts) < 3:
        return False
    if pts[0] != pts[-1]:
        pts.append(pts[0])
    total = 0.0
    for (x0, y0), (x1, y1) in zip(pts[:-1], pts[1:]):
        total += wrap(math.atan2(y1 - py, x1 - px) - math.atan2(y0 - py, x0 - px))
    return abs(total) > math.pi


@dataclass
class Drawing:
    """Nodes (drawing units) and links (node index pairs) plus the build options."""

    nodes: list[list[float]] = field(default_factory=list)
    links: list[tuple[int, int]] = field(default_factory=list)
    style: str = "insect"
    units: str = "cm"
    name: str = "creature"
    #: link thickness (drawing units) and body thickness
    thickness: float = 2.0
    body_thickness: float = 6.0

    # ----- file -----------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        return {"jackpy_creature_drawing": 1, "name": self.name, "style": self.style, "units": self.units,
                "thickness": self.thickness, "body_thickness": self.body_thickness,
                "nodes": [list(map(float, n)) for n in self.nodes], "links": [list(l) for l in self.links]}

    @classmethod
    def from_dict(cls, d: Any, file: str = "<drawing>") -> "Drawing":
        from jackpy import jsonfile as jf

        try:
            d = jf.obj(d, "")
            nodes = [jf.vector(n, f"nodes[{i}]", 2).tolist() for i, n in enumerate(jf.arr(jf.required(d, "nodes", ""), "nodes"))]
            links = []
            for i, l in enumerate(jf.arr(d.get("links", []), "links")):
                pair = jf.arr(l, f"links[{i}]")
                if len(pair) != 2:
                    raise jf.Invalid(f"links[{i}]", "expected two node indices")
                a, b = (jf.integer(v, f"links[{i}][{k}]", 0, len(nodes) - 1) for k, v in enumerate(pair))
                if a == b:
                    raise jf.Invalid(f"links[{i}]", "a link must join two different nodes")
                links.append((a, b))
            return cls(nodes, links, jf.string(d.get("style", "insect"), "style", STYLES),
                       jf.string(d.get("units", "cm"), "units", UNITS), str(d.get("name", "creature")),
                       jf.num(d.get("thickness", 2.0), "thickness", lo=1e-6),
                       jf.num(d.get("body_thickness", 6.0), "body_thickness", lo=1e-6))
        except jf.Invalid as exc:
            raise jf.schema_error(ParseError, file, exc) from None

    def save(self, path: str | os.PathLike[str]) -> None:
        from jackpy.atomic import atomic_write_text

        atomic_write_text(path, json.dumps(self.to_dict(), indent=1))

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> "Drawing":
        from jackpy import jsonfile

        try:
            data = jsonfile.load(path)
        except OSError as exc:
            raise ParseError(f"cannot read drawing: {exc.strerror or exc}", str(path)) from None
        return cls.from_dict(data, str(path))

    # ----- graph ----------------------------------------------------------------------------
    def neighbours(self) -> list[set[int]]:
        nb: list[set[int]] = [set() for _ in self.nodes]
        for a, b in self.links:
            nb[a].add(b)
            nb[b].add(a)
        return nb


class Editor:
    """Editing operations on a :class:`Drawing` with undo; the selection is a set of node indices.

    Deleting nodes renumbers the rest; every operation is one undo step.
    """

    def __init__(self, drawing: Drawing | None = None) -> None:
        self.drawing = drawing or Drawing()
        self.selection: set[int] = set()
        self._undo: list[Drawing] = []
        self._deleted: Drawing | None = None

    def _push(self) -> None:
        self._undo.append(copy.deepcopy(self.drawing))
        del self._undo[:-200]

    def undo(self) -> bool:
        if not self._undo:
            return False
        self.drawing = self._undo.pop()
        self.selection = {i for i in self.selection if i < len(self.drawing.nodes)}
        return True

    def add_node(self, x: float, y: float, connect_from: int | None = None) -> int:
        """A node at ``(x, y)`` snapped onto an axis within :data:`SNAP`; linked from ``connect_from``."""
        self._push()
        x = 0.0 if abs(x) < SNAP else float(x)
        y = 0.0 if abs(y) < SNAP else float(y)
        self.drawing.nodes.append([x, y])
        i = len(self.drawing.nodes) - 1
        if connect_from is not None:
            self.drawing.links.append((int(connect_from), i))
        return i

    def connect(self, a: int, b: int) -> None:
        if a == b or (a, b) in self.drawing.links or (b, a) in self.drawing.links:
            return
        self._push()
        self.drawing.links.append((int(a), int(b)))

    def node_at(self, x: float, y: float, radius: float = 1.5) -> int | None:
        best, bd = None, radius
        for i, (nx, ny) in enumerate(self.drawing.nodes):
            d = math.hypot(nx - x, ny - y)
            if d <= bd:
                best, bd = i, d
        return best

    def select_all(self) -> None:
        self.selection = set(range(len(self.drawing.nodes)))

    def select_lasso(self, polygon: Sequence[Sequence[float]]) -> None:
        self.selection = {i for i, p in enumerate(self.drawing.nodes) if inside_lasso(p, polygon)}

    def _transform(self, fn, copy_: bool = False) -> None:
        if not self.selection:
            return
        self._push()
        d = self.drawing
        if copy_:
            remap = {}
            for i in sorted(self.selection):
                d.nodes.append(list(d.nodes[i]))
                remap[i] = len(d.nodes) - 1
            d.links += [(remap[a], remap[b]) for a, b in list(d.links) if a in remap and b in remap]
            self.selection = set(remap.values())
        for i in self.selection:
            d.nodes[i] = [float(v) for v in fn(np.asarray(d.nodes[i], float))]

    def translate(self, dx: float, dy: float, copy_: bool = False) -> None:
        self._transform(lambda p: p + (dx, dy), copy_)

    def scale(self, sx: float, sy: float | None = None, about: Sequence[float] = (0.0, 0.0), copy_: bool = False) -> None:
        c = np.asarray(about, float)
        self._transform(lambda p: c + (p - c) * (sx, sx if sy is None else sy), copy_)

    def rotate(self, angle: float, about: Sequence[float] = (0.0, 0.0), copy_: bool = False) -> None:
        c, ca, sa = np.asarray(about, float), math.cos(angle), math.sin(angle)
        self._transform(lambda p: c + np.array([[ca, -sa], [sa, ca]]) @ (p - c), copy_)

    def mirror_x(self, copy_: bool = False) -> None:
        """Mirror the selection across the vertical axis (``x -> -x``), e.g. to copy legs across."""
        self._transform(lambda p: p * (-1.0, 1.0), copy_)

    def mirror_y(self, copy_: bool = False) -> None:
        self._transform(lambda p: p * (1.0, -1.0), copy_)

    def delete(self, nodes: Iterable[int] | None = None) -> None:
        """Delete the nodes (default: the selection) and their links; :meth:`undelete` restores."""
        gone = set(self.selection if nodes is None else nodes)
        if not gone:
            return
        self._push()
        self._deleted = copy.deepcopy(self.drawing)
        d = self.drawing
        keep = [i for i in range(len(d.nodes)) if i not in gone]
        remap = {old: new for new, old in enumerate(keep)}
        d.nodes = [d.nodes[i] for i in keep]
        d.links = [(remap[a], remap[b]) for a, b in d.links if a in remap and b in remap]
        self.selection = set()

    def undelete(self) -> bool:
        if self._deleted is None:
            return False
        self._push()
        self.drawing, self._deleted = self._deleted, None
        return True


@dataclass
class Appendage:
    kind: str  # "leg", "head", "tail"
    nodes: list[int]  # base first, tip last


@dataclass
class Analysis:
    body: list[int]
    appendages: list[Appendage]

    @property
    def legs(self) -> list[Appendage]:
        return [a for a in self.appendages if a.kind == "leg"]

    def of(self, kind: str) -> list[Appendage]:
        return [a for a in self.appendages if a.kind == kind]


def analyse(drawing: Drawing) -> Analysis:
    """Sims 4.2 network analysis (see the module docstring for our head/tail rule)."""
    nb = drawing.neighbours()
    n = len(drawing.nodes)
    comp, best = [-1] * n, []
    for s in range(n):
        if comp[s] >= 0:
            continue
        stack, members = [s], []
        comp[s] = s
        while stack:
            u = stack.pop()
            members.append(u)
            for v in nb[u]:
                if comp[v] < 0:
                    comp[v] = s
                    stack.append(v)
        if len(members) > len(best):
            best = members
    keep = set(best)
    if len(keep) < 3:
        raise FigureError(f"drawing {drawing.name!r}: its largest connected part has fewer than 3 nodes")
    deg = {u: len(nb[u] & keep) for u in keep}
    apps: list[list[int]] = []
    for tip in sorted(u for u in keep if deg[u] == 1):
        chain, prev, cur = [tip], None, tip
        while True:
            nxt = [v for v in nb[cur] if v in keep and v != prev]
            if not nxt:
                break
            prev, cur = cur, nxt[0]
            chain.append(cur)
            if deg[cur] > 2:
                break
        if deg[cur] <= 2:
            raise FigureError(f"drawing {drawing.name!r}: a chain with no body (draw a body with branches)")
        apps.append(chain[::-1])
    in_app = {u for a in apps for u in a[1:]}
    body = sorted(u for u in keep if u not in in_app)
    P = np.asarray(drawing.nodes, float)
    front, back = min(body, key=lambda u: P[u, 1]), max(body, key=lambda u: P[u, 1])
    out = []
    for a in apps:
        d = P[a[-1]] - P[a[0]]
        ang = math.degrees(math.atan2(abs(d[0]), -d[1]))  # 0 = straight ahead (-y)
        kind = "leg"
        if a[0] == front and ang < 30 and not any(x.kind == "head" for x in out):
            kind = "head"
        elif a[0] == back and ang > 150 and not any(x.kind == "tail" for x in out):
            kind = "tail"
        out.append(Appendage(kind, a))
    return Analysis(body, out)


def _to_world(drawing: Drawing, p: Sequence[float]) -> np.ndarray:
    u = UNITS[drawing.units]
    return np.array([-p[0] * u, 0.0, -p[1] * u])


def _box_mesh() -> Mesh:
    v = np.array([[x, y, z] for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)])
    f = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1], [2, 3, 7], [2, 7, 6],
         [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    return Mesh(v, np.array(f))


def box_psurf_text() -> str:
    """The unit box (1 m, centred) every built segment's geometry scales, as psurf text (cm)."""
    m = _box_mesh()
    lines = ["# jackpy creature box: 100 cm cube centred on the origin (scaled per segment)"]
    lines += [f"v {x * 100:g} {y * 100:g} {z * 100:g}" for x, y, z in m.vertices]
    lines += ["f " + " ".join(str(i + 1) for i in face) for face in m.faces]
    return "\n".join(lines) + "\n"


def _rotation_to(d: np.ndarray) -> np.ndarray:
    """A rotation taking +x onto unit ``d``."""
    from scipy.spatial.transform import Rotation

    x = np.array([1.0, 0.0, 0.0])
    axis = np.cross(x, d)
    s, c = np.linalg.norm(axis), float(x @ d)
    if s < 1e-12:
        return np.eye(3) if c > 0 else np.diag([-1.0, 1.0, -1.0])
    return Rotation.from_rotvec(axis / s * math.atan2(s, c)).as_matrix()


def _box(center: np.ndarray, rot: np.ndarray, size: Sequence[float]) -> Psurf:
    M = np.eye(4)
    M[:3, :3] = rot @ np.diag(size)
    M[:3, 3] = center
    return Psurf(BOX_PSURF, M, _box_mesh())


def _box_inertia(mass: float, rot: np.ndarray, size: Sequence[float]) -> np.ndarray:
    a, b, c = size
    I = mass / 12.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])
    return rot @ I @ rot.T


UP = np.array([0.0, 1.0, 0.0])


def build(drawing: Drawing, *, link_density: float = 1.0, body_density: float = 20.0) -> Figure:
    """The 3-D Peabody figure of ``drawing`` (see the module docstring). Masses: links
    ``link_density`` kg/m of length, the body ``body_density`` kg/m^2 of its drawn footprint
    (at least 0.2 kg); inertias of the boxes they are drawn as."""
    if drawing.style not in STYLES:
        raise FigureError(f"style must be one of {', '.join(STYLES)}, not {drawing.style!r}")
    an = analyse(drawing)
    if not an.legs:
        raise FigureError(f"drawing {drawing.name!r} has no legs")
    u = UNITS[drawing.units]
    W = {i: _to_world(drawing, p) for i, p in enumerate(drawing.nodes)}
    body_pts = np.array([W[i] for i in an.body])
    centre = body_pts.mean(axis=0)
    fig = Figure(drawing.name)
    lo, hi = body_pts.min(axis=0), body_pts.max(axis=0)
    th = drawing.body_thickness * u
    size = np.maximum(hi - lo, th) + [0.0, 0.0, 0.0]
    size[1] = th
    bmass = max(0.2, body_density * (size[0] * size[2]))
    body = Segment("body", psurf=_box((lo + hi) / 2 - centre, np.eye(3), size), attribute="olivedrab",
                   mass=bmass, com=np.zeros(3), inertia=_box_inertia(bmass, np.eye(3), size))
    body.add_site("centre")
    fig.add_segment(body)
    counts = {"l": 0, "r": 0, "head": 0, "tail": 0}
    order = sorted(an.appendages, key=lambda a: (a.kind != "leg", -W[a.nodes[0]][2], a.nodes[0]))
    for app in order:
        base_w = W[app.nodes[0]]
        side = "l" if (W[app.nodes[-1]][0] - centre[0]) >= 0 else "r"
        key = side if app.kind == "leg" else app.kind
        counts[key] += 1
        tag = f"leg_{side}{counts[side]}" if app.kind == "leg" else f"{app.kind}{counts[key]}"
        parent, parent_site_pos = "body", base_w - centre
        nlinks = len(app.nodes) - 1
        dirs = [(W[b] - W[a]) / max(np.linalg.norm(W[b] - W[a]), 1e-12) for a, b in zip(app.nodes[:-1], app.nodes[1:])]
        for k in range(nlinks):
            a, b = W[app.nodes[k]], W[app.nodes[k + 1]]
            L = float(np.linalg.norm(b - a))
            if L < 1e-9:
                raise FigureError(f"drawing {drawing.name!r}: two linked nodes lie on top of each other")
            name = f"{tag}_{k + 1}"
            rot = _rotation_to(dirs[k])
            w = drawing.thickness * u
            mass = link_density * L
            seg = Segment(name, psurf=_box((b - a) / 2, rot, (L, w, w)), attribute="darkkhaki", mass=mass,
                          com=(b - a) / 2, inertia=_box_inertia(mass, rot, (L, w, w)))
            seg.add_site("proximal")
            tipname = "foot" if (k == nlinks - 1 and app.kind == "leg") else ("tip" if k == nlinks - 1 else "distal")
            seg.add_site(tipname, _trans(b - a))
            fig.add_segment(seg)
            site_name = f"{name}_joint"
            fig.segments[parent].add_site(site_name, _trans(parent_site_pos))
            d_in = dirs[k - 1] if k > 0 else dirs[k]
            horiz = np.cross(UP, d_in + dirs[k])
            horiz = horiz / np.linalg.norm(horiz) if np.linalg.norm(horiz) > 1e-9 else np.array([0.0, 0.0, 1.0])
            dofs = _joint_dofs(drawing.style, app.kind, k, horiz)
            fig.add_joint(Joint(name, parent, site_name, name, "proximal", dofs))
            parent, parent_site_pos = name, b - a
    fig.root = ("body", "centre")
    _stand(fig, drawing.style)
    return fig


def _trans(p: np.ndarray) -> np.ndarray:
    M = np.eye(4)
    M[:3, 3] = p
    return M


def _joint_dofs(style: str, kind: str, k: int, horiz: np.ndarray) -> list[Dof]:
    r = math.radians
    if kind != "leg":
        return [Dof("R", horiz, -r(60), r(60))]
    if style == "insect":
        if k == 0:  # ball: inner lift about the horizontal axis, outer yaw
            return [Dof("R", horiz, -r(100), r(100)), Dof("R", UP, -r(60), r(60))]
        return [Dof("R", horiz, -r(170), r(170))]
    if k == 0:  # mammal ball: inner fore-aft swing (vertical in creation), outer fold about the horizontal
        return [Dof("R", UP, -r(120), r(120)), Dof("R", horiz, -r(30), r(120))]
    return [Dof("R", UP, -r(170), r(170))]


def _stand(fig: Figure, style: str) -> None:
    """Set the default posture (module docstring) and place the root so the lowest foot touches
    ``y = 0``."""
    legs: dict[str, list[str]] = {}
    for jn in fig.joints:
        if jn.startswith("leg_"):
            legs.setdefault(jn.rsplit("_", 1)[0], []).append(jn)
    for chain in legs.values():
        n = len(chain)
        if style == "insect":
            # absolute elevations of the links: +30 deg first, -75 deg last; rotation -e about the
            # horizontal axis raises by e (up x d rotated by +theta lowers d)
            elev = [30.0] if n == 1 else list(np.linspace(30.0, -75.0, n))
            prev = 0.0
            for k, jn in enumerate(chain):
                j = fig.joints[jn]
                delta = -math.radians(elev[k] - prev)
                j.displacement = np.array([delta, 0.0]) if k == 0 else np.array([delta])
                prev = elev[k]
        else:
            for k, jn in enumerate(chain):
                j = fig.joints[jn]
                bend = math.radians(70.0) * (1 if k % 2 else -1) * (0.5 if k == 0 else 1.0)
                j.displacement = np.array([bend, math.radians(80.0)]) if k == 0 else np.array([bend])
    fig.location = np.eye(4)
    kin = fig.kinematics()
    fk = kin.forward(fig.q, fig.location)
    low = min((fk.segments[kin.segment_index[s.name]] @ s.sites["foot"].location)[1, 3]
              for s in fig.segments.values() if "foot" in s.sites)
    fig.location = _trans(np.array([0.0, -low, 0.0]))


def save_figure(fig: Figure, path: str | os.PathLike[str]) -> None:
    """Write ``fig`` as a ``.fig`` with its box geometry file beside it (atomically, each)."""
    from jackpy.atomic import atomic_write_text
    from jackpy.peabody.writer import write_figures

    box = Path(path).absolute().parent / BOX_PSURF
    text = box_psurf_text()
    if not box.exists() or box.read_text() != text:
        atomic_write_text(box, text)
    write_figures(path, [fig])
