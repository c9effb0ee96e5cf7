"""A synthetic human-shaped tree of Jack's size (69 segments, 136 DOFs) for tests and benchmarks.

It has the topology of the standard human (pelvis root, 17 vertebrae, neck, head, jaw, eyes, two arms
with clavicle and 15 phalanges, two legs) with plain box-free segments (no geometry) and rough
masses, so kinematics and IK can be exercised before and apart from :mod:`jackpy.body`.
"""

from __future__ import annotations

import numpy as np

from jackpy.peabody.model import Dof, Figure, Joint, Segment
from jackpy.peabody.transforms import translation

X, Y, Z = (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)


def _dofs(axes: list[tuple[float, float, float]], limit_deg: float) -> list[Dof]:
    lim = np.radians(limit_deg)
    return [Dof("R", np.array(a), -lim, lim) for a in axes]


def human_like_tree() -> Figure:
    """Build the 69-segment, 136-DOF tree standing with its pelvis 1 m above the floor."""
    f = Figure("synthetic_human")

    def seg(name: str, length: float, mass: float, tip_dir: tuple[float, float, float] = Y) -> Segment:
        s = Segment(name, mass=mass, com=np.array(tip_dir) * length / 2)
        s.add_site("base")
        s.add_site("tip", translation(*(np.array(tip_dir) * length)))
        return f.add_segment(s)

    def join(name: str, parent: str, site: str, child: str, axes: list, limit: float = 60.0) -> None:
        f.add_joint(Joint(name, parent, site, child, "base", _dofs(axes, limit)))

    pelvis = seg("pelvis", 0.1, 10.0)
    for side, sx in (("left", 1.0), ("right", -1.0)):
        pelvis.add_site(f"hip_{side}", translation(0.09 * sx, -0.05, 0.0))
    prev = "pelvis"
    for k in range(17):
        name = f"vertebra{k + 1}"
        seg(name, 0.028, 1.2)
        join(f"spine{k + 1}", prev, "tip", name, [X, Z, Y], 8.0)
        prev = name
    seg("neck", 0.1, 1.0)
    join("neck", prev, "tip", "neck", [X, Z, Y], 40.0)
    head = seg("head", 0.22, 4.5)
    join("head", "neck", "tip", "head", [X, Z, Y], 40.0)
    head.add_site("jaw", translation(0.0, 0.05, 0.05))
    seg("jaw", 0.06, 0.3, (0.0, -0.5, 0.5))
    join("jaw", "head", "jaw", "jaw", [X], 25.0)
    for side, sx in (("left", 1.0), ("right", -1.0)):
        head.add_site(f"eye_{side}", translation(0.032 * sx, 0.1, 0.08))
        seg(f"eye_{side}", 0.012, 0.01, Z)
        join(f"eye_{side}", "head", f"eye_{side}", f"eye_{side}", [Y, X], 35.0)
        top = f.segment(prev)
        top.add_site(f"clav_{side}", translation(0.02 * sx, 0.0, 0.0))
        out = (sx, 0.0, 0.0)
        down = (0.0, -1.0, 0.0)
        seg(f"clavicle_{side}", 0.16, 0.2, out)
        join(f"clavicle_{side}", prev, f"clav_{side}", f"clavicle_{side}", [Z, Y], 20.0)
        seg(f"upperarm_{side}", 0.3, 2.0, down)
        join(f"shoulder_{side}", f"clavicle_{side}", "tip", f"upperarm_{side}", [X, Z, Y], 90.0)
        seg(f"forearm_{side}", 0.26, 1.2, down)
        join(f"elbow_{side}", f"upperarm_{side}", "tip", f"forearm_{side}", [X], 75.0)
        palm = seg(f"palm_{side}", 0.09, 0.4, down)
        join(f"wrist_{side}", f"forearm_{side}", "tip", f"palm_{side}", [Y, X, Z], 60.0)
        for d in range(5):
            palm.add_site(f"mcp{d}", translation(sx * (0.04 - 0.02 * d), -0.09, 0.0))
            parent, site = f"palm_{side}", f"mcp{d}"
            for p in range(3):
                name = f"finger{d}{p}_{side}"
                seg(name, 0.03, 0.01, down)
                axes = [X, Z] if p == 0 else [X]
                join(name, parent, site, name, axes, 45.0)
                parent, site = name, "tip"
        seg(f"thigh_{side}", 0.44, 8.0, down)
        join(f"hip_{side}", "pelvis", f"hip_{side}", f"thigh_{side}", [X, Z, Y], 90.0)
        seg(f"shank_{side}", 0.42, 3.5, down)
        join(f"knee_{side}", f"thigh_{side}", "tip", f"shank_{side}", [X], 70.0)
        seg(f"foot_{side}", 0.08, 1.0, down)
        join(f"ankle_{side}", f"shank_{side}", "tip", f"foot_{side}", [X, Z, Y], 30.0)
        f.segment(f"foot_{side}").add_site("ball", translation(0.0, -0.08, 0.15))
        seg(f"toes_{side}", 0.05, 0.2, Z)
        join(f"toes_{side}", f"foot_{side}", "ball", f"toes_{side}", [X], 30.0)
    f.root = ("pelvis", "base")
    f.location = translation(0.0, 1.0, 0.0)
    return f
