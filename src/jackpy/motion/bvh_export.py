"""BVH export of baked motion in the figure's own hierarchy, and its exact re-import.

The hierarchy is the figure's segment tree from the pelvis (the first segment when there is no
pelvis), each BVH joint named after its segment. A segment's BVH frame is its base frame moved to
the site of its parent joint on its own side (so the joint centre is the BVH joint's origin); the
OFFSET is where that site sits in the parent's BVH frame, constant for rotational joints. The
root has ``Xposition Yposition Zposition`` then, like every joint, rotation channels in the order
**Zrotation Xrotation Yrotation** (R = Rz Rx Ry, intrinsic, degrees). Lengths are
**centimetres**, y up, as jackpy's world. Leaf segments get an End Site at their farthest site.

Reading such a file back (:func:`import_own`, chosen when every BVH joint is one of the figure's
segments) solves each joint's displacements from its BVH rotation (Gauss-Newton on the joint's own
axes, warm-started frame to frame, clamped to its limits), so the sites come back where they were
(well under 1 mm).
"""

from __future__ import annotations

import os
from collections.abc import Callable

import numpy as np
from scipy.spatial.transform import Rotation

from jackpy.atomic import atomic_write_text
from jackpy.motion.bvh import BVH, BVHJoint, format_bvh

ORDER = "ZXY"
CM = 100.0


def hierarchy(figure) -> list[tuple[str, int, str | None, str | None, str | None]]:
    """(segment, parent index, parent-side site, own-side site, joint name) per BVH joint, in the
    depth-first order a BVH file lists them (parents first)."""
    root = "pelvis" if "pelvis" in figure.segments else next(iter(figure.segments))
    out: list[tuple[str, int, str | None, str | None, str | None]] = []
    seen = {root}

    def visit(seg: str, parent: int, psite: str | None, own: str | None, jname: str | None) -> None:
        k = len(out)
        out.append((seg, parent, psite, own, jname))
        for j in figure.joints.values():
            if j.from_seg == seg and j.to_seg not in seen:
                seen.add(j.to_seg)
                visit(j.to_seg, k, j.from_site, j.to_site, j.name)
            elif j.to_seg == seg and j.from_seg not in seen:
                seen.add(j.from_seg)
                visit(j.from_seg, k, j.to_site, j.from_site, j.name)

    visit(root, -1, None, None, None)
    return out


def _frames(figure, tree, world: dict[str, np.ndarray]) -> list[np.ndarray]:
    """BVH frame (4x4 world) of each entry of ``tree`` at the posture with segment transforms ``world``."""
    out = []
    for seg, parent, _, own, _ in tree:
        f = world[seg] if own is None else world[seg] @ figure.site_location(seg, own)
        out.append(f)
    return out


def skeleton(figure) -> tuple[list[BVHJoint], list, list[np.ndarray]]:
    """BVH joints (cm offsets, channels), the tree, and each joint's constant rotation ``R_A`` (the
    parent-side site frame in the parent's BVH frame)."""
    tree = hierarchy(figure)
    world = figure.world_transforms()
    frames = _frames(figure, tree, world)
    joints, fixed = [], []
    children = {p for _, p, _, _, _ in tree}
    for k, (seg, parent, psite, own, _) in enumerate(tree):
        ch = ["Xposition", "Yposition", "Zposition"] if parent < 0 else []
        ch += [f"{a}rotation" for a in ORDER]
        if parent < 0:
            offset, ra = np.zeros(3), np.eye(3)
        else:
            pseg = tree[parent][0]
            a = np.linalg.inv(frames[parent]) @ world[pseg] @ figure.site_location(pseg, psite)
            offset, ra = a[:3, 3] * CM, a[:3, :3]
        end = None
        if k not in children:
            sites = [s for s in figure.segment(seg).sites if s != own]
            if sites:
                inv = np.linalg.inv(frames[k])
                pts = [(inv @ world[seg] @ figure.site_location(seg, s))[:3, 3] for s in sites]
                end = max(pts, key=lambda p: float(np.linalg.norm(p))) * CM
        joints.append(BVHJoint(seg, parent, offset, ch, end))
        fixed.append(ra)
    first = 0
    for j in joints:
        j.first_channel = first
        first += len(j.channels)
    return joints, tree, fixed


def motion_rows(figure, baked, tree) -> np.ndarray:
    """Channel values (N, channels) of every baked frame."""
    rows = []
    for i in range(baked.n_frames):
        baked.posture(figure, i).apply_to(figure)
        world = figure.world_transforms()
        frames = _frames(figure, tree, world)
        row = []
        for k, (seg, parent, _, _, _) in enumerate(tree):
            local = frames[k] if parent < 0 else np.linalg.inv(frames[parent]) @ frames[k]
            if parent < 0:
                row += list(local[:3, 3] * CM)
            row += list(Rotation.from_matrix(local[:3, :3]).as_euler(ORDER, degrees=True))
        rows.append(row)
    return np.array(rows)


def write_bvh(figure, baked, fps: float, path: str | os.PathLike) -> None:
    """Write ``baked`` (a :class:`~jackpy.motion.motion_file.BakedFigure` of ``figure``) as BVH."""
    from jackpy.body.human import set_neutral_posture

    try:
        set_neutral_posture(figure)  # offsets are read at rest; they are the same at any posture
    except Exception:  # not a standard human: its current posture serves
        pass
    joints, tree, _ = skeleton(figure)
    rows = motion_rows(figure, baked, tree)
    atomic_write_text(path, format_bvh(joints, rows, 1.0 / fps))


def is_own(figure, bvh: BVH) -> bool:
    """Whether ``bvh`` is in ``figure``'s own hierarchy (every joint a segment, same count)."""
    return len(bvh.joints) == len(figure.segments) and all(n in figure.segments for n in bvh.names)


def _rotvec(r: np.ndarray) -> np.ndarray:
    return Rotation.from_matrix(r).as_rotvec()


def _gauss_newton(joint, target: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Displacements from ``q`` reducing the rotation error to ``target`` (rotational DOFs)."""
    q = q.astype(float).copy()
    for _ in range(25):
        mats = [d.transform(v)[:3, :3] for d, v in zip(joint.dofs, q)]
        total = np.eye(3)
        for m in mats:
            total = m @ total
        r = _rotvec(total @ target.T)
        if np.linalg.norm(r) < 1e-13:
            break
        # angular velocity of each DOF, in the joint's from-site frame (D = D_n ... D_1)
        cols, after = [], np.eye(3)
        for k in range(len(mats) - 1, -1, -1):
            cols.append(after @ joint.dofs[k].axis)
            after = after @ mats[k]
        omega = np.stack(cols[::-1], axis=1)
        step = np.linalg.lstsq(omega, -r, rcond=None)[0]
        q += step
        if np.linalg.norm(step) < 1e-14:
            break
    return q


def _into_limits(joint, q: np.ndarray) -> np.ndarray:
    """Shift angles by whole turns into their limits where that is possible."""
    q = q.copy()
    for k in range(q.size):
        for turn in (-2 * np.pi, 2 * np.pi):
            if not joint.lower[k] <= q[k] <= joint.upper[k] and joint.lower[k] <= q[k] + turn <= joint.upper[k]:
                q[k] += turn
    return q


def _solve_joint(joint, target: np.ndarray, q0: np.ndarray) -> np.ndarray:
    """Displacements of ``joint`` whose rotation is ``target`` (3x3), within its limits: Gauss-Newton
    from the last frame's values, then (when that lands outside the limits or misses) from other
    starts (zero, the middle of the limits, each angle turned by half a turn)."""
    lo, hi = joint.lower, joint.upper
    starts = [q0, np.zeros(q0.size), 0.5 * (lo + hi)]
    starts += [q0 + np.pi * np.array([1.0 if i in (a, b) else 0.0 for i in range(q0.size)]) * s
               for a in range(q0.size) for b in range(q0.size) if a <= b for s in (1.0, -1.0)]
    best, best_key = None, None
    for start in starts:
        q = _into_limits(joint, _gauss_newton(joint, target, start))
        mats = np.eye(3)
        for d, v in zip(joint.dofs, q):
            mats = d.transform(v)[:3, :3] @ mats
        res = float(np.linalg.norm(_rotvec(mats @ target.T)))
        viol = float(np.max(np.maximum(lo - q, q - hi), initial=0.0))
        key = (viol > 1e-9, res + viol)
        if best_key is None or key < best_key:
            best, best_key = q, key
        if viol <= 1e-9 and res < 1e-9:
            break
    return np.clip(best, lo, hi)


def import_own(figure, bvh: BVH, fps: float, progress: Callable[[int, int], None] | None = None) -> list:
    """Postures of ``figure`` for ``bvh`` written by :func:`write_bvh` (resampled to ``fps``)."""
    from jackpy.body.human import set_neutral_posture
    from jackpy.motion.bake import Posture
    from jackpy.motion.retarget import resample

    try:
        set_neutral_posture(figure)
    except Exception:
        pass
    _, tree, fixed = skeleton(figure)
    order = {name: k for k, name in enumerate(bvh.names)}
    idx = resample(bvh.frames.shape[0], bvh.fps, fps, 0)
    rot, trans = bvh.local(bvh.frames[idx])
    root_seg = tree[0][0]
    root_site = figure.root[1] if figure.root and figure.root[0] == root_seg else next(iter(figure.segment(root_seg).sites))
    figure.reroot(root_seg, root_site)
    out = []
    for i in range(len(idx)):
        for k, (seg, parent, psite, own, jname) in enumerate(tree):
            if parent < 0:
                continue
            b = order[seg]
            d = fixed[k].T @ rot[i, b]
            j = figure.joint(jname)
            if j.to_seg != seg:  # traversed up: the BVH rotation is D^-1
                d = d.T
            j.displacement = _solve_joint(j, d, j.displacement)
        b = order[root_seg]
        w = np.eye(4)
        w[:3, :3] = rot[i, b]
        w[:3, 3] = trans[i, b] / CM
        figure.location = w @ figure.site_location(root_seg, root_site)
        out.append(Posture.of(figure))
        if progress is not None:
            progress(i + 1, len(idx))
    return out
