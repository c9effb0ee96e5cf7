"""jackpy against mink (differential IK on MuJoCo, QP per step) on the same 91-variable human.

The problem (issue 20's table): the standard 50th-percentile male with a 6-DOF floating root, the
spine (17 vertebral joints, 51 DOFs), both arms (clavicle 2, shoulder tilt 1, shoulder 3, elbow 1,
forearm twist 2, wrist 2: 2 x 11) and both legs (hip 3, knee 1, ankle 2: 2 x 6); every other joint
locked, no joint groups (mink has no spine or shoulder drivers). Goals: both palm centres to target
frames, both feet held where they stand. Success: every goal within 1 mm and 1 deg; both solvers
stop at that same test.

- jackpy: the figure gains a ``world`` segment and two joints (translation x, y, z; rotation) as its
  floating root; ``ik.solve`` with ``PositionOrientation`` goals (1 deg costs as much as 1 cm).
- mink: the same figure exported by :mod:`jackpy.motion.robot_export` as MJCF with a free joint and
  the locked joints welded; ``FrameTask`` per goal, ``ConfigurationLimit``, ``solve_ik`` with the
  daqp QP solver and damping 1e-3, one ``integrate_inplace`` per iteration.

Both run interleaved in one process, from the same start, on the same targets. Targets come from a
random posture of the spine and arms (root and legs neutral, so the held feet stay reachable) at half
the range of motion (``ik-vs-mink-cold``; extras ``full_*`` at the full range), and for
``ik-vs-mink-drag`` from a left palm dragged 1 cm per frame out and back. Without mink the rows say
"skipped: pip install jackpy[bench]".

MuJoCo's warnings while a row runs are counted in its ``mujoco_warnings`` extra instead of printed
into the table: loading the export warns once that the joint-space inertia is singular at the zero
posture (the shoulder's Euler joint at gimbal lock, docs/robot-export.md); it does not touch the
kinematics either solver uses.
"""

from __future__ import annotations

import contextlib
import time
from collections.abc import Iterator

import numpy as np

from jackpy import ik
from jackpy.bench.runner import Case, Result
from jackpy.peabody.model import Dof, Figure, Joint, Segment

TOL_M, TOL_DEG = 1e-3, 1.0
SPINE = ["l5_s1", "l4_l5", "l3_l4", "l2_l3", "l1_l2", "t12_l1"] + [f"t{k}_t{k + 1}" for k in range(11, 0, -1)]
ARM = ["clavicle", "shoulder_tilt", "shoulder", "elbow", "forearm_twist_1", "forearm_twist_2", "wrist"]
LEG = ["hip", "knee", "ankle"]
MOVING = SPINE + [f"{s}_{j}" for s in ("left", "right") for j in ARM + LEG]
PALMS = ("left_palm.palm_centre", "right_palm.palm_centre")
FEET = ("left_foot.base", "right_foot.base")
ROOT_JOINTS = ("root_translation", "root_rotation")
ORIENTATION = ik.unit_factor(1.0, 0.01)  # 1 deg of misalignment costs as much as 1 cm
SKIPPED = "skipped: pip install jackpy[bench]"
MINK_MAX_ITERATIONS = 100


def human() -> Figure:
    """The standard male without joint groups (its raw DOFs are the variables)."""
    from jackpy.body import make_human

    fig = make_human("male", 50)
    fig.groups = {}
    fig.topology_changed()
    return fig


def floating(fig: Figure) -> Figure:
    """``fig`` with a 6-DOF root: world.origin -T(x,y,z)-> root_link -R(y,x,z)-> the old root site."""
    seg, site = fig.root
    world = fig.add_segment(Segment("world"))
    world.add_site("origin")
    link = fig.add_segment(Segment("root_link"))
    link.add_site("base")
    fig.add_joint(Joint("root_translation", "world", "origin", "root_link", "base",
                        [Dof("T", axis, -2.0, 2.0) for axis in ((1, 0, 0), (0, 1, 0), (0, 0, 1))]))
    fig.add_joint(Joint("root_rotation", "root_link", "base", seg, site,
                        [Dof("R", axis, -np.pi, np.pi) for axis in ((0, 0, 1), (1, 0, 0), (0, 1, 0))]))
    location = fig.location.copy()
    fig.root = ("world", "origin")
    fig.location = location
    fig.topology_changed()
    return fig


class JackpySide:
    """jackpy's problem on the floating human."""

    def __init__(self) -> None:
        self.figure = floating(human())
        p = ik.Problem(self.figure)
        p.lock(*[j for j in self.figure.joints if j not in MOVING and j not in ROOT_JOINTS])
        self.goals = [p.add(ik.PositionOrientation(s, np.eye(4), cx=ORIENTATION)) for s in PALMS + FEET]
        self.problem = p
        assert p.compile().nv == 91, p.compile().nv
        self.neutral = self.figure.q

    def set_targets(self, targets: list[np.ndarray]) -> None:
        for g, t in zip(self.goals, targets):
            g.target = t

    def solve(self) -> tuple[bool, float, int]:
        t0 = time.perf_counter()
        r = ik.solve(self.problem, tol_position=TOL_M, tol_angle=TOL_DEG)
        ms = (time.perf_counter() - t0) * 1e3
        return all(g.metres <= TOL_M and g.degrees <= TOL_DEG for g in r.goals), ms, r.iterations


class MinkSide:
    """mink's problem on the same human, through the MJCF export."""

    def __init__(self, fig: Figure) -> None:
        import mink
        import mujoco

        from jackpy.motion.robot_export import to_mjcf

        self.mink, self.mujoco = mink, mujoco
        frozen = [j for j in fig.joints if j not in MOVING]
        self.model = mujoco.MjModel.from_xml_string(to_mjcf(fig, floating=True, frozen=frozen))
        assert self.model.nv == 91, self.model.nv
        data = mujoco.MjData(self.model)
        mujoco.mj_resetData(self.model, data)
        self.neutral = data.qpos.copy()
        self.configuration = mink.Configuration(self.model, self.neutral)
        self.tasks = [mink.FrameTask(s, "site", position_cost=1.0, orientation_cost=1.0, lm_damping=0.0)
                      for s in PALMS + FEET]
        self.limits = [mink.ConfigurationLimit(self.model)]
        self.site_ids = [self.model.site(s).id for s in PALMS + FEET]
        self.targets: list[np.ndarray] = []

    def set_targets(self, targets: list[np.ndarray]) -> None:
        self.targets = targets
        for task, t in zip(self.tasks, targets):
            task.set_target(self.mink.SE3.from_matrix(t))

    def achieved(self) -> bool:
        d = self.configuration.data
        for sid, t in zip(self.site_ids, self.targets):
            if np.linalg.norm(d.site_xpos[sid] - t[:3, 3]) > TOL_M:
                return False
            R = d.site_xmat[sid].reshape(3, 3).T @ t[:3, :3]
            if np.degrees(np.arccos(np.clip((np.trace(R) - 1.0) / 2.0, -1.0, 1.0))) > TOL_DEG:
                return False
        return True

    def solve(self, max_iterations: int = MINK_MAX_ITERATIONS) -> tuple[bool, float, int]:
        t0 = time.perf_counter()
        conf, it = self.configuration, 0
        ok = self.achieved()
        while not ok and it < max_iterations:
            v = self.mink.solve_ik(conf, self.tasks, 1.0, "daqp", damping=1e-3, limits=self.limits)
            conf.integrate_inplace(v, 1.0)
            it += 1
            ok = self.achieved()
        return ok, (time.perf_counter() - t0) * 1e3, it


def _available() -> bool:
    try:
        import daqp  # noqa: F401
        import mink  # noqa: F401
        import mujoco  # noqa: F401
    except ImportError:
        return False
    return True


@contextlib.contextmanager
def _mujoco_warnings() -> Iterator[list[str]]:
    """MuJoCo's warnings inside the block, collected (not printed); the previous handler after."""
    import mujoco

    seen: list[str] = []
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(seen.append)
    try:
        yield seen
    finally:
        mujoco.set_mju_user_warning(previous)


def _skipped(name: str) -> Result:
    return Result(name, float("nan"), float("nan"), None, {"status": SKIPPED})


def _pair() -> tuple[JackpySide, MinkSide, list[np.ndarray]]:
    ours = JackpySide()
    peer = MinkSide(human())
    feet = [ours.figure.site_world(*s.split(".", 1)) for s in FEET]
    return ours, peer, feet


def _palm_targets(ours: JackpySide, rng: np.random.Generator, fraction: float) -> list[np.ndarray]:
    """Palm frames at a random posture: spine and arm DOFs uniform in ``fraction`` of their limits."""
    fig = ours.figure
    q = ours.neutral.copy()
    lo, hi = fig.lower, fig.upper
    for j in MOVING:
        if any(j.endswith(leg) for leg in LEG):
            continue
        sl = fig.joint_dof_slice(j)
        q[sl] = rng.uniform(lo[sl], hi[sl]) * fraction
    fig.q = q
    out = [fig.site_world(*s.split(".", 1)) for s in PALMS]
    fig.q = ours.neutral
    return out


def _stats(prefix: str, runs: list[tuple[bool, float, int]]) -> dict[str, float]:
    t = np.array([r[1] for r in runs])
    return {f"{prefix}ms": float(np.median(t)), f"{prefix}p90": float(np.percentile(t, 90)),
            f"{prefix}success": float(np.mean([r[0] for r in runs])),
            f"{prefix}iters": float(np.median([r[2] for r in runs]))}


def _cold_runs(ours: JackpySide, peer: MinkSide, feet: list[np.ndarray], rng: np.random.Generator,
               fraction: float, n: int) -> tuple[list, list]:
    a, b = [], []
    for i in range(n):
        targets = _palm_targets(ours, rng, fraction) + feet
        for side in ((ours, peer) if i % 2 == 0 else (peer, ours)):  # alternate who runs first
            side.set_targets(targets)
            if side is ours:
                ours.figure.q = ours.neutral
                a.append(ours.solve())
            else:
                peer.configuration.update(peer.neutral)
                b.append(peer.solve())
    return a, b


def cold(quick: bool) -> Result:
    if not _available():
        return _skipped("ik-vs-mink-cold")
    with _mujoco_warnings() as warned:
        ours, peer, feet = _pair()
        rng = np.random.default_rng(20)
        n = 20 if quick else 200
        a, b = _cold_runs(ours, peer, feet, rng, 0.5, n)
        fa, fb = _cold_runs(ours, peer, feet, rng, 1.0, n // 2)
    sa, sb = _stats("", a), _stats("", b)
    extra = {"n": n, "p90_ratio": sa["p90"] / sb["p90"], "success": sa["success"], "mink_p90": sb["p90"],
             "mink_success": sb["success"], "iters": sa["iters"], "mink_iters": sb["iters"],
             "mujoco_warnings": len(warned)}
    full_a, full_b = _stats("full_", fa), _stats("full_mink_", fb)
    extra.update({k: full_a[k] for k in ("full_ms", "full_p90", "full_success", "full_iters")})
    extra.update({k: full_b[k] for k in ("full_mink_ms", "full_mink_p90", "full_mink_success", "full_mink_iters")})
    return Result("ik-vs-mink-cold", sa["ms"], sa["p90"], sb["ms"], extra)


def drag(quick: bool) -> Result:
    if not _available():
        return _skipped("ik-vs-mink-drag")
    with _mujoco_warnings() as warned:  # the export's load (module docstring)
        ours, peer, feet = _pair()
    rng = np.random.default_rng(21)
    targets = _palm_targets(ours, rng, 0.3) + feet
    for side in (ours, peer):
        side.set_targets(targets)
        side.solve()
    step = np.array([0.6, 0.48, 0.64]) * 0.01 / np.linalg.norm([0.6, 0.48, 0.64])  # 1 cm per frame
    frames = 50 if quick else 200
    a, b = [], []
    for k in range(frames):
        t = targets[0].copy()
        t[:3, 3] += step if (k // 25) % 2 == 0 else -step  # 25 cm out and back along a line
        targets = [t] + targets[1:]
        for side in ((ours, peer) if k % 2 == 0 else (peer, ours)):
            side.set_targets(targets)
            (a if side is ours else b).append(side.solve())
    sa, sb = _stats("", a), _stats("", b)
    return Result("ik-vs-mink-drag", sa["ms"], sa["p90"], sb["ms"],
                  {"frames": frames, "success": sa["success"], "mink_p90": sb["p90"],
                   "mink_success": sb["success"], "iters": sa["iters"], "mink_iters": sb["iters"],
                   "mujoco_warnings": len(warned)})


CASES = [
    Case("ik-vs-mink-cold", cold, "91-variable floating human, palms to targets, feet held: jackpy vs mink, from neutral"),
    Case("ik-vs-mink-drag", drag, "same problem, left palm dragged 1 cm/frame, warm start: jackpy vs mink"),
]
