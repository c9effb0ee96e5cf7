"""Eye view, view cones and visibility from the eyes (book §5.1.1 Z-buffer perception; behaviors
§2.8 head and eyes).

Visibility of an object is measured in its silhouette as seen from the eye point: a camera at the
eye aims at the target's bounding sphere; the target is rendered alone (its silhouette ``A``) and
then with every occluder, each body drawn in a flat ID colour (``B``). The visible fraction is
``|A and B == target| / |A|``; pixels of ``A`` covered by another body name that body as an
occluder, with the share of the silhouette it hides. A site (a point on an object) is treated as a
small disc facing the eye: it is hidden where a surface lies more than ``tol`` in front of it (the
site's own surface passes through the site, so a tolerance is needed).

Field of view [proposal; common ergonomics figures, e.g. MIL-STD-1472]: view cones about the gaze
line with half-angles 15 deg (optimum eye rotation), 35 deg (maximum eye rotation), 60 deg
(binocular field), 94 deg (monocular, temporal limit). The eye-view camera uses a 90 deg vertical
and 4:3 aspect picture (about 106 deg horizontal): the most a flat picture shows without heavy
distortion.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from jackpy.render.bodies import Body, BodyRenderer
from jackpy.render.projection import linear_depth, look_at, perspective_matrix
from jackpy.analysis.parts import figure_parts
from jackpy.body.skin import segment_surfaces
from jackpy.peabody.model import Environment, Figure

#: (name, half-angle radians) from narrowest to widest
VIEW_CONES: tuple[tuple[str, float], ...] = (
    ("optimum", np.radians(15.0)),
    ("maximum eye rotation", np.radians(35.0)),
    ("binocular", np.radians(60.0)),
    ("peripheral", np.radians(94.0)),
)
EYE_VIEW_FOVY = np.radians(90.0)
EYE_VIEW_ASPECT = 4.0 / 3.0


@dataclass(frozen=True)
class EyeView:
    """The figure's eye point and gaze (world, metres; unit ``forward`` and ``up``)."""

    position: np.ndarray
    forward: np.ndarray
    up: np.ndarray

    def view_matrix(self) -> np.ndarray:
        """World-to-camera transform looking along the gaze."""
        return look_at(self.position, self.position + self.forward, self.up)

    def projection(self, near: float = 0.02, far: float = 50.0) -> np.ndarray:
        """The eye camera's perspective (see the module docstring for the field of view)."""
        return perspective_matrix(EYE_VIEW_FOVY, EYE_VIEW_ASPECT, near, far)

    def angle_to(self, point: np.ndarray) -> float:
        """Angle (radians) between the gaze and the line from the eye to ``point``."""
        d = np.asarray(point, dtype=float) - self.position
        c = d @ self.forward / max(np.linalg.norm(d), 1e-12)
        return float(np.arccos(np.clip(c, -1.0, 1.0)))

    def cone(self, point: np.ndarray) -> str | None:
        """The narrowest view cone holding ``point``; ``None`` outside the visual field."""
        a = self.angle_to(point)
        return next((name for name, half in VIEW_CONES if a <= half), None)


def eye_view(figure: Figure) -> EyeView:
    """The eye view of a standard or synthetic human at its current posture."""
    p, f, u = figure_parts(figure).eyes.world(figure)
    return EyeView(p, f / np.linalg.norm(f), u / np.linalg.norm(u))


@dataclass
class Visibility:
    """Visible ``fraction`` (0..1) of a target from the eye, the share of its silhouette each
    occluder hides (by body name), and the ``pixels`` its silhouette covered in the measurement."""

    target: str
    fraction: float
    occluders: dict[str, float] = field(default_factory=dict)
    pixels: int = 0


def figure_bodies(figure: Figure, exclude_containing: np.ndarray | None = None) -> list[Body]:
    """A body per segment with geometry, named ``figure.segment`` (a standard human's torso as its
    posed skin, :func:`jackpy.body.skin.segment_surfaces`); segments whose world bounding box holds
    ``exclude_containing`` (the head and eyes around the eye point) are left out."""
    world = figure.world_transforms()
    out = []
    for name, mesh in segment_surfaces(figure, world).items():
        t = world[name]
        if exclude_containing is not None:
            v = mesh.vertices @ t[:3, :3].T + t[:3, 3]
            if np.all(v.min(axis=0) <= exclude_containing) and np.all(exclude_containing <= v.max(axis=0)):
                continue
        colour = tuple(getattr(figure, "colour", (0.75, 0.75, 0.78))) + (1.0,)
        out.append(Body(name if len(figure.segments) == 1 else f"{figure.name}.{name}", mesh, t, colour))
    return out


def environment_bodies(env: Environment, exclude: set[str] = frozenset(),
                       eye: np.ndarray | None = None) -> list[Body]:
    """Bodies of every figure in ``env`` not named in ``exclude``; see :func:`figure_bodies`."""
    out = []
    for name, fig in env.figures.items():
        if name not in exclude:
            out.extend(figure_bodies(fig, eye))
    return out


def _bounding_sphere(bodies: list[Body]) -> tuple[np.ndarray, float]:
    pts = np.vstack([b.mesh.vertices @ b.model[:3, :3].T + b.model[:3, 3] for b in bodies])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    c = (lo + hi) / 2
    return c, float(np.linalg.norm(pts - c, axis=1).max())


def object_visibility(renderer: BodyRenderer, eye: np.ndarray, target: list[Body],
                      occluders: list[Body], name: str) -> Visibility:
    """Visible fraction of the ``target`` bodies from ``eye`` past ``occluders`` (module docstring)."""
    centre, radius = _bounding_sphere(target)
    d = float(np.linalg.norm(centre - eye))
    fovy = 2 * np.arcsin(min(radius / d, 0.95)) * 1.05 if d > 1e-9 else np.radians(120)
    view = look_at(eye, centre if d > 1e-9 else eye + [0, 0, 1])
    proj = perspective_matrix(min(fovy, np.radians(150)), renderer.size[0] / renderer.size[1], 0.005, d + radius + 1.0)
    alone, _ = renderer.render_ids(target, view, proj)
    mask = alone > 0
    total = int(mask.sum())
    if total == 0:
        return Visibility(name, 0.0, {}, 0)
    ids, _ = renderer.render_ids(target + occluders, view, proj)
    seen = mask & (ids >= 1) & (ids <= len(target))
    hidden = ids[mask & ~seen]
    occ: dict[str, float] = {}
    for k, count in zip(*np.unique(hidden[hidden > len(target)], return_counts=True)):
        nm = occluders[int(k) - len(target) - 1].name
        occ[nm] = occ.get(nm, 0.0) + count / total
    return Visibility(name, float(seen.sum()) / total, dict(sorted(occ.items(), key=lambda kv: -kv[1])), total)


def point_visibility(renderer: BodyRenderer, eye: np.ndarray, point: np.ndarray,
                     occluders: list[Body], name: str, radius: float = 0.002, tol: float = 0.01) -> Visibility:
    """Visible fraction of a disc of ``radius`` at ``point`` facing ``eye``; surfaces less than
    ``tol`` (metres) in front of the point do not hide it."""
    d = float(np.linalg.norm(point - eye))
    near, far = min(0.005, d / 2), d + 1.0
    view = look_at(eye, point)
    w, h = renderer.size
    half = np.arctan(radius / d)
    proj = perspective_matrix(2 * half * 1.25, w / h, near, far)
    ids, depth = renderer.render_ids(occluders, view, proj)
    yy, xx = np.mgrid[0:h, 0:w]
    r_pix = (h / 2) / 1.25
    disc = (xx + 0.5 - w / 2) ** 2 + (yy + 0.5 - h / 2) ** 2 <= r_pix ** 2
    blocked = disc & (ids > 0) & (linear_depth(depth, near, far) < d - tol)
    total = int(disc.sum())
    occ: dict[str, float] = {}
    for k, count in zip(*np.unique(ids[blocked], return_counts=True)):
        nm = occluders[int(k) - 1].name
        occ[nm] = occ.get(nm, 0.0) + count / total
    return Visibility(name, 1.0 - float(blocked.sum()) / total, dict(sorted(occ.items(), key=lambda kv: -kv[1])), total)
