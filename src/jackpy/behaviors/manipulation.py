"""The seven manipulation commands of Jack ([SH4] Table 4.6; behaviors.md §3) plus grabbing and grasping.

A workbench drag calls one of these per mouse event, then :meth:`BehaviorLoop.step` once per frame,
and :func:`end_drag` on mouse release. Commands only write goals into the loop's state; the
behaviors respond (feet stay planted, balance is kept, the figure steps when it must). A gesture
translates *or* rotates; while it translates, behaviors choose the orientation.

All positions are world metres, rotations world 3x3 (or 4x4) matrices, angles radians.
"""

from __future__ import annotations

import numpy as np

from jackpy.behaviors.grasp import GraspObject, GraspParams, GraspResult, close_fingers, palm_goal, preshape
from jackpy.behaviors.loop import BehaviorLoop
from jackpy.behaviors.state import Attachment, FootState, HandState, SeatState
from jackpy.behaviors.support import floor, yaw_of
from jackpy.behaviors.torso import MODES, bend_spine
from jackpy.peabody.transforms import rigid_inverse, rotation_matrix

OTHER = {"left": "right", "right": "left"}


def _pose(loop: BehaviorLoop, seg_site: tuple[str, str]) -> np.ndarray:
    return loop.figure.site_world(*seg_site)


def move_hand(loop: BehaviorLoop, side: str, position: np.ndarray | None = None,
              rotation: np.ndarray | None = None, lean: bool = False) -> None:
    """Move hand ``side``'s palm goal to ``position`` (translation: the palm rules pick the
    orientation) and/or to ``rotation`` (the user's orientation). ``lean`` lets an out-of-reach
    goal recruit the body and, at the edge of balance, a step."""
    hs = loop.state.hands[side]
    if hs.goal is None:
        hs.goal = _pose(loop, loop.anatomy.hands[side].palm).copy()
    hs.local = None
    if position is not None:
        hs.goal[:3, 3] = np.asarray(position, dtype=float)[:3]
        hs.rules = rotation is None
    if rotation is not None:
        hs.goal[:3, :3] = np.asarray(rotation, dtype=float)[:3, :3]
        hs.rules = False
    hs.orient = True
    hs.lean = lean


def hand_on_site(loop: BehaviorLoop, side: str, pose: np.ndarray) -> None:
    """Reach hand ``side``'s palm site to the world pose ``pose`` and hold it there."""
    move_hand(loop, side, rotation=pose)
    loop.state.hands[side].goal[:3, 3] = np.asarray(pose)[:3, 3]


def release_hand(loop: BehaviorLoop, side: str) -> None:
    """Remove hand ``side``'s constraint (the arm stays where it is)."""
    hs = loop.state.hands[side]
    hs.goal, hs.local, hs.lean, hs.rules = None, None, False, False


def grab(loop: BehaviorLoop, side: str, obj: object) -> None:
    """Attach ``obj`` (with a ``pose``) to hand ``side``: it follows the hand (the screwdriver model)."""
    palm = _pose(loop, loop.anatomy.hands[side].palm)
    loop.state.hands[side].attached.append(Attachment(obj, rigid_inverse(palm) @ obj.pose))


def release(loop: BehaviorLoop, side: str, obj: object | None = None) -> None:
    """Detach ``obj`` (or every object) from hand ``side``; it stays where it is."""
    hs = loop.state.hands[side]
    hs.attached = [a for a in hs.attached if obj is not None and a.obj is not obj]


def grasp(loop: BehaviorLoop, side: str, obj: GraspObject, grip: str = "power", frames: int = 40,
          attach: bool = True) -> GraspResult:
    """Kinematic grasp ([SH4] §4.2.7): preshape, reach the palm to the grip site (running up to
    ``frames`` frames), close the grip's digits onto ``obj`` and, with ``attach``, grab it."""
    h = loop.anatomy.hands[side]
    preshape(loop.figure, h, grip)
    goal = palm_goal(h, loop.figure.site_location(*h.palm), obj, grip)
    hand_on_site(loop, side, goal)
    for _ in range(frames):
        loop.step()
        if np.linalg.norm(_pose(loop, h.palm)[:3, 3] - goal[:3, 3]) < 5e-4:
            break
    result = close_fingers(loop.figure, h, obj, GraspParams(grip=grip))
    if attach:
        grab(loop, side, obj)
    return result


def move_foot(loop: BehaviorLoop, side: str, position: np.ndarray | None = None,
              rotation: np.ndarray | None = None) -> None:
    """Drag foot ``side``'s ball-site goal; the support moves to the other foot for the drag."""
    st = loop.state
    fs = st.feet[side]
    if st.root == side:
        loop.set_root(OTHER[side])
    st.root_claimed = True
    if position is not None:
        fs.target[:3, 3] = np.asarray(position, dtype=float)[:3]
    if rotation is not None:
        fs.target[:3, :3] = np.asarray(rotation, dtype=float)[:3, :3]


def set_foot_behavior(loop: BehaviorLoop, side: str, mode: str | None = None, heel: str | None = None) -> None:
    """Foot ``side``: ``mode`` "pivot" or "hold"; ``heel`` "floor" (keep on floor) or "free" (may rise)."""
    fs = loop.state.feet[side]
    if mode is not None:
        if mode not in ("pivot", "hold"):
            raise ValueError(f"foot mode must be 'pivot' or 'hold', not {mode!r}")
        fs.mode = mode
    if heel is not None:
        if heel not in ("floor", "free"):
            raise ValueError(f"heel must be 'floor' or 'free', not {heel!r}")
        fs.heel = heel


def sit(loop: BehaviorLoop, seat_height: float, footrest_height: float = 0.0) -> bool:
    """Seat the figure (a standard human) erect on a seat ``seat_height`` high, feet flat on a
    footrest ``footrest_height`` high where the shanks reach (:func:`jackpy.body.seated.sit`; the arms
    hang at the neutral elevation); from then on the seat behavior keeps the ischia on the seat and
    the feet behavior the feet where they rest, until :func:`stand_up`. A foot that cannot reach the
    footrest hangs, held where it is. Goals of hands, pelvis, torso and COM are cleared. Heights are
    world y (m); returns whether both feet rest on the footrest."""
    from jackpy.body.seated import seat_contact_points
    from jackpy.body.seated import sit as seat_figure
    from jackpy.body.skeleton import NEUTRAL_ARM_ELEVATION

    fig, st, a = loop.figure, loop.state, loop.anatomy
    # rooted at the pelvis, upright, facing where the pelvis faces: sit() bends the hips about it
    loop.set_root("pelvis")
    site = fig.site_location(a.pelvis, a.pelvis_site)
    yaw = yaw_of(fig.location[:3, :3] @ (site[:3, :3].T @ a.pelvis_forward))
    loc = fig.location.copy()
    loc[:3, :3] = rotation_matrix(np.array([0.0, 1.0, 0.0]), yaw)[:3, :3] @ site[:3, :3]
    fig.location = loc
    resting = seat_figure(fig, seat_height, footrest_height)
    for side in a.hands:
        g = fig.groups.get(f"{side}_shoulder_complex")
        if g is not None:
            theta = g.angles.copy()
            theta[list(g.angle_names).index("elevation")] = np.radians(NEUTRAL_ARM_ELEVATION)
            g.set_angles(fig, theta)
    st.seat = SeatState(float(seat_height), float(footrest_height), seat_contact_points(fig), resting)
    st.root_claimed = True
    st.feet = {}
    for side, spec in a.feet.items():
        on_rest = abs(fig.site_world(*spec.heel)[1, 3] - footrest_height) < 0.002
        st.feet[side] = FootState(fig.site_world(*spec.ball), "pivot" if on_rest else "hold",
                                  "floor" if on_rest else "free")
    st.hands = {s: HandState() for s in a.hands}
    st.pelvis_goal, st.pelvis_user, st.torso_goal, st.com_drag = None, False, None, None
    return resting


def stand_up(loop: BehaviorLoop) -> None:
    """Leave the seated mode: the seat is cleared and the automatic root chooses the root again
    (the posture stays; drag the pelvis or feet to stand)."""
    loop.state.seat = None
    loop.state.root_claimed = False


def move_com(loop: BehaviorLoop, point: np.ndarray) -> None:
    """Drag the balance point to the floor point under world ``point`` (the weight shifts; the
    figure steps when it reaches the edge of the feet)."""
    loop.state.com_drag = floor(np.asarray(point, dtype=float)[:3])


def set_balance(loop: BehaviorLoop, x: float, z: float = 0.0) -> None:
    """Set the balance parameters: ``x`` weight share on the right foot, ``z`` front/back (±1 edges)."""
    loop.state.balance = (float(x), float(z))
    loop.state.com_drag = None


def move_pelvis(loop: BehaviorLoop, rotation: np.ndarray | None = None,
                translation: np.ndarray | None = None) -> None:
    """Rotate the pelvis goal to world ``rotation`` (curl, tilt, twist; the feet stay planted, the
    torso stays vertical); or translate it by ``translation`` (m), which drags the balance point."""
    st = loop.state
    if rotation is not None:
        st.pelvis_goal = np.asarray(rotation, dtype=float)[:3, :3].copy()
        st.pelvis_user = True
    if translation is not None:
        base = st.com_drag if st.com_drag is not None else st.balance_point
        st.com_drag = base + floor(np.asarray(translation, dtype=float)[:3])


def bend_torso(loop: BehaviorLoop, flexion: float, lateral: float = 0.0, axial: float = 0.0) -> np.ndarray:
    """Bend the spine to totals (rad) by forward kinematics; the torso then keeps that bend (the
    hips move back to keep balance). Returns the angles applied."""
    loop.state.torso_mode = "bend"
    return bend_spine(loop.figure, loop.anatomy, flexion, lateral, axial)


def set_torso_behavior(loop: BehaviorLoop, mode: str) -> None:
    """Torso ``mode``: "vertical" (default), "hold" (current global orientation) or "bend"."""
    if mode not in MODES:
        raise ValueError(f"torso mode must be one of {MODES}, not {mode!r}")
    loop.state.torso_mode = mode
    loop.state.torso_goal = None


def move_head(loop: BehaviorLoop, point: np.ndarray | None) -> None:
    """Fixate the head (neck only) on world ``point``; None releases it."""
    loop.state.head_target = None if point is None else np.asarray(point, dtype=float)[:3].copy()


def move_eyes(loop: BehaviorLoop, point: np.ndarray | None) -> None:
    """Fixate the eyes on world ``point`` (the head follows when they run out); None releases them."""
    loop.state.eyes_target = None if point is None else np.asarray(point, dtype=float)[:3].copy()


def end_drag(loop: BehaviorLoop) -> None:
    """Mouse release: the COM drag becomes stored (x, z); the user lets go of the pelvis; feet
    goals are kept; hands keep their goals (the orientation ratchet starts from there)."""
    st = loop.state
    st.com_drag = None
    st.pelvis_user = False
    if not any(getattr(b, "step", None) for b in loop.behaviors):
        st.root_claimed = False
    for hs in st.hands.values():
        hs.rules = False
