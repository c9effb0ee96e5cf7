"""Workplace-analysis benchmarks: an arm's reachable workspace and per-frame clearance.

- ``reach-workspace``: the right arm of the 50th-percentile male (clavicle to grip, 11 DOFs) sampled
  into a 64³ grid until converged. Baseline: the same number of reference points by one
  :meth:`Kinematics.forward` per sample (timed on 2000 samples and scaled; extra ``baseline`` says so).
- ``clearance-frame``: the standard human against a 100k-triangle object in front of it, the right
  arm moving each frame: collisions with the object, self-collisions and the minimum clearance
  (the object's distance grid is built before timing, as a workbench builds it on the first query).
  Baseline: no broad phase and no pruning (every segment's collision and distance against the
  object each frame).
"""

from __future__ import annotations

import time

import numpy as np

from jackpy.bench.runner import Case, Result, time_calls


def _human():
    from jackpy.body import make_human

    return make_human("male", 50)


def _workspace_case(quick: bool) -> Result:
    from jackpy.analysis.parts import figure_parts
    from jackpy.analysis.workspace import Chain, reachable_workspace

    f = _human()
    hand = figure_parts(f).hands["right"]
    chain = Chain.to_site(f, hand.start_joint, hand.segment, hand.site)
    holder: dict = {}

    def ours() -> None:
        holder["ws"] = reachable_workspace(chain, 64)

    t = time_calls(ours, repeat=1 if quick else 3, warmup=0 if quick else 1)
    ws = holder["ws"]
    kin = f.kinematics()
    rng = np.random.default_rng(0)
    q = np.tile(f.q, (2000, 1))
    q[:, chain.dofs] = rng.uniform(chain.lower, chain.upper, (2000, len(chain.dofs)))
    t0 = time.perf_counter()
    for row in q:
        kin.forward(row, f.location)
    per_sample = (time.perf_counter() - t0) / 2000
    return Result("reach-workspace", t.median_ms, t.p90_ms, per_sample * ws.samples * 1e3,
                  {"dofs": len(chain.dofs), "samples": ws.samples, "voxels": int(ws.occupied.sum()),
                   "volume_m3": ws.volume(), "converged": ws.converged, "baseline": "scaled from 2000 FK calls"})


def _object(triangles: int = 100_000):
    import trimesh

    from jackpy.peabody.geometry import Mesh
    from jackpy.scene.cad import CADObject, ImportSettings

    n = int(np.sqrt(triangles / 4))
    m = trimesh.creation.uv_sphere(radius=0.25, count=[n, n])
    obj = CADObject("ball", ImportSettings("ball.ply"), Mesh(m.vertices, m.faces))
    return obj


def _clearance_case(quick: bool) -> Result:
    from jackpy.analysis.clearance import ClearanceChecker
    from jackpy.analysis.parts import figure_parts

    f = _human()
    obj = _object()
    grip = f.site_world(figure_parts(f).hands["right"].segment, "grip")[:3, 3]
    obj.place(grip + np.array([0.0, 0.35, 0.45]))
    chk = ClearanceChecker(f, [obj])
    chk.clearance("ball")  # builds the object's distance grid (once per object)
    q0 = f.q
    dofs = np.r_[f.joint_dof_slice("right_shoulder"), f.joint_dof_slice("right_elbow")]
    frames = [q0.copy() for _ in range(60)]
    for k, q in enumerate(frames):  # raise the arm forward towards the ball and back
        s = np.sin(np.pi * k / len(frames))
        q[dofs] = np.clip(q0[dofs] + s * 1.2 * np.sign(f.upper[dofs]), f.lower[dofs], f.upper[dofs])
    state = {"k": 0, "hits": 0, "min": np.inf}

    def frame() -> None:
        q = frames[state["k"] % len(frames)]
        state["k"] += 1
        chk.update(q)
        state["hits"] += len(chk.object_collisions()) + len(chk.self_collisions())
        state["min"] = min(state["min"], chk.clearance("ball").distance)

    def brute() -> None:  # no broad phase, no pruning: every segment against the object
        import fcl

        q = frames[state["k"] % len(frames)]
        state["k"] += 1
        chk.update(q)
        ball = chk._body_obj[0]
        for s in range(len(chk.segment_names)):
            fcl.collide(chk._place(s), ball, fcl.CollisionRequest(), fcl.CollisionResult())
            fcl.distance(chk._place(s), ball, fcl.DistanceRequest(), fcl.DistanceResult())

    repeat = 60 if quick else 240
    t = time_calls(frame, repeat=repeat, warmup=5)
    base = time_calls(brute, repeat=5 if quick else 20, warmup=1)
    faces = sum(len(s.psurf.mesh.faces) for s in f.segments.values() if s.psurf is not None and s.psurf.mesh is not None)
    return Result("clearance-frame", t.median_ms, t.p90_ms, base.median_ms,
                  {"object_triangles": obj.triangle_count, "figure_triangles": faces,
                   "segments": len(chk.segment_names), "self_pairs": len(chk._pairs),
                   "min_clearance_m": state["min"]})


CASES = [
    Case("reach-workspace", _workspace_case, "right-arm reachable workspace, 64^3 voxels, until converged"),
    Case("clearance-frame", _clearance_case, "human vs 100k-triangle object: collisions + min clearance per frame"),
]
