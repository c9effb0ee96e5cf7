"""Anthropometric dimensions measured FROM a generated figure, the way a surveyor measures a subject.

Every function puts a copy of the figure's posture into the survey posture the definition asks for
(standing erect, or sitting erect on a flat seat with thighs horizontal and knees at 90°), measures
world positions of **surface vertices and sites by forward kinematics**, and restores the figure's
posture. Nothing is read from the population tables. Results are metres (kilograms for ``weight``).

Definitions follow ANSUR II (Gordon et al. 2014, NATICK/TR-15/007, Appendix C); the measuring
posture and what the figure offers for each landmark are said per function. Floor: the lowest
vertex of the foot surfaces. Seat: the lowest vertex of the pelvis and thigh surfaces in the sitting
posture (a hard flat seat, as in the survey). Use :func:`measure` / :func:`measure_all`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager

import numpy as np

from jackpy.errors import FigureError
from jackpy.peabody.model import Figure

SIDES = ("left", "right")
#: segments whose surfaces make up the torso (pelvis and the 17 vertebral slabs)
TORSO = ("pelvis", "l5", "l4", "l3", "l2", "l1") + tuple(f"t{k}" for k in range(12, 0, -1))
#: the spine joints of the standard human (survey postures straighten them)
_SIT_HIP_FLEXION = np.radians(90.0)
_SIT_KNEE_FLEXION = np.radians(90.0)


# ---- posture helpers ----------------------------------------------------------------------------
@contextmanager
def _kept_posture(fig: Figure) -> Iterator[Figure]:
    q, loc = fig.q, fig.location.copy()
    angles = {n: g.angles.copy() for n, g in fig.groups.items()}
    try:
        yield fig
    finally:
        for n, g in fig.groups.items():
            g.angles = angles[n]
        fig.q = q
        fig.location = loc


def _set_group(fig: Figure, name: str, **values: float) -> None:
    g = fig.groups[name]
    theta = g.angles.copy()
    for k, v in values.items():
        theta[g.angle_names.index(k)] = v
    g.set_angles(fig, theta)


def _zero_posture(fig: Figure, arm_elevation: float = 0.0, arm_abduction: float = 0.0) -> None:
    """Every displacement and group angle 0; shoulder complexes at the given elevation/abduction (rad)."""
    fig.q = np.zeros(fig.ndof)
    for g in fig.groups.values():
        g.set_angles(fig, np.zeros(g.nangles))
    for side in SIDES:
        name = f"{side}_shoulder_complex"
        if name in fig.groups:
            _set_group(fig, name, elevation=arm_elevation, abduction=arm_abduction)


def _set_dof(fig: Figure, joint: str, k: int, value: float) -> None:
    j = fig.joint(joint)
    d = j.displacement.copy()
    d[k] = value
    j.displacement = d


def standing_posture(fig: Figure, arm_elevation: float = 0.0, arm_abduction: float = 0.0) -> None:
    """Survey standing posture: erect, heels together in the zero pose, arms at the given shoulder
    elevation (rad; 0 = hanging), lowest foot vertex on y = 0."""
    _zero_posture(fig, arm_elevation, arm_abduction)
    _place(fig, floor=_lowest(fig, _feet(fig)))


def sitting_posture(fig: Figure) -> None:
    """Survey sitting posture: trunk erect, thighs horizontal (hip flexion 90°), knees at 90°, feet
    flat, arms hanging; the figure is moved so its lowest foot vertex is on y = 0."""
    _zero_posture(fig)
    for side in SIDES:
        _set_dof(fig, f"{side}_hip", _dof_index(fig, f"{side}_hip", "flexion"), _SIT_HIP_FLEXION)
        _set_dof(fig, f"{side}_knee", 0, _SIT_KNEE_FLEXION)
    _place(fig, floor=_lowest(fig, _feet(fig)))


def _dof_index(fig: Figure, joint: str, dof: str) -> int:
    from jackpy.body.skeleton import dof_names_of

    return dof_names_of(fig.joint(joint)).index(dof)


def _place(fig: Figure, floor: float) -> None:
    fig.location = fig.location.copy()
    fig.location[1, 3] -= floor


# ---- geometry from the figure -------------------------------------------------------------------
def surface_points(fig: Figure, segments: tuple[str, ...] | list[str]) -> np.ndarray:
    """World positions (n, 3) of the surface vertices of ``segments`` at the current posture."""
    world = fig.world_transforms()
    out = []
    for name in segments:
        seg = fig.segment(name)
        mesh = seg.psurf.posed_mesh() if seg.psurf is not None else None
        if mesh is None:
            raise FigureError(f"figure {fig.name!r}: segment {name!r} has no surface to measure")
        t = world[name]
        out.append(mesh.vertices @ t[:3, :3].T + t[:3, 3])
    return np.concatenate(out)


def site_point(fig: Figure, seg: str, site: str) -> np.ndarray:
    """World position (3,) of ``seg.site``."""
    return fig.site_world(seg, site)[:3, 3].copy()


def _feet(fig: Figure) -> list[str]:
    return [f"{s}_{p}" for s in SIDES for p in ("foot", "toes")]


def _lowest(fig: Figure, segments: list[str]) -> float:
    return float(surface_points(fig, segments)[:, 1].min())


def _head_top(fig: Figure) -> float:
    return float(surface_points(fig, ["head"])[:, 1].max())


def seat_height(fig: Figure) -> float:
    """In the sitting posture: height (m) of the lowest vertex of the pelvis and thigh surfaces,
    i.e. the hard flat seat the figure sits on."""
    return _lowest(fig, ["pelvis"] + [f"{s}_thigh" for s in SIDES])


def _eye_y(fig: Figure) -> float:
    return float(np.mean([site_point(fig, f"{s}_eye", "base")[1] for s in SIDES]))


# ---- the dimensions -----------------------------------------------------------------------------
def stature(fig: Figure) -> float:
    """STATURE: vertical distance from the floor to the top of the head (vertex), standing erect,
    barefoot. Figure: highest head-surface vertex above the lowest foot-surface vertex."""
    with _kept_posture(fig):
        standing_posture(fig)
        return _head_top(fig)


def eye_height_standing(fig: Figure) -> float:
    """EYE HEIGHT (standing; ANSUR 1988, not an ANSUR II item): floor to the outer corner of the eye
    (ectocanthus), standing erect. Figure: mean height of the eyeball centres (``<side>_eye.base``),
    which lie at the level of the eye corners."""
    with _kept_posture(fig):
        standing_posture(fig)
        return _eye_y(fig)


def eye_height_sitting(fig: Figure) -> float:
    """EYE HEIGHT, SITTING: vertical distance from the sitting surface to the ectocanthus, sitting
    erect. Figure: eyeball-centre height above :func:`seat_height` in the sitting posture."""
    with _kept_posture(fig):
        sitting_posture(fig)
        return _eye_y(fig) - seat_height(fig)


def sitting_height(fig: Figure) -> float:
    """SITTING HEIGHT: vertical distance from the sitting surface to the top of the head, sitting
    erect. Figure: highest head vertex above :func:`seat_height` in the sitting posture."""
    with _kept_posture(fig):
        sitting_posture(fig)
        return _head_top(fig) - seat_height(fig)


def acromial_height(fig: Figure) -> float:
    """ACROMIAL HEIGHT: floor to the acromion (the lateral tip of the shoulder blade's spine),
    standing, arms hanging. Figure: mean height of the ``<side>_clavicle.acromion`` sites."""
    with _kept_posture(fig):
        standing_posture(fig)
        return float(np.mean([site_point(fig, f"{s}_clavicle", "acromion")[1] for s in SIDES]))


def knee_height_sitting(fig: Figure) -> float:
    """KNEE HEIGHT, SITTING: vertical distance from the footrest (floor) to the top of the knee
    (the thigh's upper surface just above the kneecap), sitting, knees at 90°, feet flat. Figure:
    highest thigh/shank vertex within 4 cm (horizontally) of the knee joint centre."""
    with _kept_posture(fig):
        sitting_posture(fig)
        tops = []
        for s in SIDES:
            knee = site_point(fig, f"{s}_shank", "base")
            pts = surface_points(fig, [f"{s}_thigh", f"{s}_shank"])
            near = np.abs(pts[:, 2] - knee[2]) < 0.04
            tops.append(pts[near, 1].max())
        return float(np.mean(tops))


def buttock_knee_length(fig: Figure) -> float:
    """BUTTOCK-KNEE LENGTH: horizontal distance from the rearmost point of the buttocks to the front
    of the kneecaps, sitting. Figure: frontmost thigh/shank vertex minus the rearmost vertex of the
    pelvis and lower lumbar slabs, along the facing direction (+z)."""
    with _kept_posture(fig):
        sitting_posture(fig)
        back = surface_points(fig, ["pelvis", "l5", "l4"])[:, 2].min()
        front = surface_points(fig, [f"{s}_{p}" for s in SIDES for p in ("thigh", "shank")])[:, 2].max()
        return float(front - back)


def hip_breadth_sitting(fig: Figure) -> float:
    """HIP BREADTH, SITTING: maximum horizontal breadth across the hips or thighs, sitting, knees
    together. Figure: extent along x of the pelvis and thigh surfaces in the sitting posture."""
    with _kept_posture(fig):
        sitting_posture(fig)
        x = surface_points(fig, ["pelvis"] + [f"{s}_thigh" for s in SIDES])[:, 0]
        return float(x.max() - x.min())


def chest_breadth(fig: Figure) -> float:
    """CHEST BREADTH: horizontal breadth of the chest (not the arms) at the level of the nipples /
    bust point, standing. Figure: the bust-point level is where the torso surface stands furthest
    forward in its upper half; the breadth is the x extent of the torso vertices within 1 cm of it."""
    with _kept_posture(fig):
        standing_posture(fig)
        pts = surface_points(fig, list(TORSO[6:]))  # thoracic slabs
        bust_y = pts[np.argmax(pts[:, 2]), 1]
        band = pts[np.abs(pts[:, 1] - bust_y) < 0.01]
        return float(band[:, 0].max() - band[:, 0].min())


def bideltoid_breadth(fig: Figure) -> float:
    """BIDELTOID BREADTH: maximum horizontal breadth across the shoulders between the lateral bulges
    of the deltoid muscles, standing, upper arms hanging. Figure: x extent of the clavicle and
    upper-arm surfaces in the standing posture."""
    with _kept_posture(fig):
        standing_posture(fig)
        x = surface_points(fig, [f"{s}_{p}" for s in SIDES for p in ("clavicle", "upper_arm")])[:, 0]
        return float(x.max() - x.min())


def arm_span(fig: Figure) -> float:
    """SPAN: distance between the tips of the middle fingers with both arms outstretched
    horizontally to the sides (shoulder elevation 90° in the lateral plane), fingers straight.
    Figure: distance between the ``<side>_middle_3.tip`` sites."""
    with _kept_posture(fig):
        standing_posture(fig, arm_elevation=np.pi / 2)
        return float(np.linalg.norm(site_point(fig, "left_middle_3", "tip")
                                    - site_point(fig, "right_middle_3", "tip")))


def hand_length(fig: Figure) -> float:
    """HAND LENGTH: from the wrist crease (stylion line) to the tip of the middle finger, hand and
    fingers straight. Figure: wrist joint centre (``<side>_palm.base``) to the middle fingertip
    (``<side>_middle_3.tip``), mean of both hands, zero pose."""
    with _kept_posture(fig):
        standing_posture(fig)
        return float(np.mean([np.linalg.norm(site_point(fig, f"{s}_middle_3", "tip")
                                              - site_point(fig, f"{s}_palm", "base")) for s in SIDES]))


def foot_length(fig: Figure) -> float:
    """FOOT LENGTH: maximum length of the foot, heel to the tip of the longest toe, standing,
    measured along the foot axis. Figure: z extent of the foot and toe surfaces of each foot (the
    shoe's surface when the figure wears shoes), mean of both feet."""
    with _kept_posture(fig):
        standing_posture(fig)
        lengths = []
        for s in SIDES:
            z = surface_points(fig, [f"{s}_foot", f"{s}_toes"])[:, 2]
            lengths.append(z.max() - z.min())
        return float(np.mean(lengths))


def weight(fig: Figure) -> float:
    """WEIGHT (body mass, kg): the sum of the segment masses."""
    return fig.total_mass


#: every measure by its ANSUR-style name
MEASURES: dict[str, Callable[[Figure], float]] = {
    "stature": stature,
    "eye_height_standing": eye_height_standing,
    "eye_height_sitting": eye_height_sitting,
    "sitting_height": sitting_height,
    "acromial_height": acromial_height,
    "knee_height_sitting": knee_height_sitting,
    "buttock_knee_length": buttock_knee_length,
    "hip_breadth_sitting": hip_breadth_sitting,
    "chest_breadth": chest_breadth,
    "bideltoid_breadth": bideltoid_breadth,
    "arm_span": arm_span,
    "hand_length": hand_length,
    "foot_length": foot_length,
    "weight": weight,
}


def measure(fig: Figure, name: str) -> float:
    """The dimension ``name`` (a key of :data:`MEASURES`) measured from ``fig``: metres, kg for weight.
    The figure's posture is unchanged afterwards."""
    try:
        fn = MEASURES[name]
    except KeyError:
        raise FigureError(f"unknown measure {name!r} (known: {', '.join(MEASURES)})") from None
    return fn(fig)


def measure_all(fig: Figure) -> dict[str, float]:
    """Every dimension of :data:`MEASURES` measured from ``fig``."""
    return {name: fn(fig) for name, fn in MEASURES.items()}
