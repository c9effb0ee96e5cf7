"""Benchmark: drawing the standard human with its continuous skins (vertex-shader skinning).

``skin-draw``: one offscreen frame (640x480, no MSAA, pixels read back so the GPU work is timed) of
the 50th-percentile man with the spine bent 60 degrees and twisted 30, scene built by the window's
``SceneView``. Baseline: the same frame with the rigid segment surfaces (the scene's skins dropped,
so the 18 torso slabs, arms and legs are drawn as instances). Extra: building the skins once (ms).
"""

from __future__ import annotations

import time

import numpy as np

from jackpy.bench.runner import Case, Result, time_calls


def _skin_draw(quick: bool) -> Result:
    from jackpy.body import make_human
    from jackpy.body.skin import build_skins
    from jackpy.peabody import Environment
    from jackpy.render import look_at, offscreen_renderer, perspective_matrix
    from jackpy.ui.scene_view import SceneView

    fig = make_human("male", 50)
    fig.groups["spine"].set_angles(fig, np.radians([60.0, 0.0, 30.0]))
    t0 = time.perf_counter()
    build_skins(fig)
    build_ms = (time.perf_counter() - t0) * 1e3
    env = Environment()
    env.figures[fig.name] = fig
    renderer = offscreen_renderer(640, 480, samples=0)
    view = SceneView()
    view.upload(renderer, env)
    c = fig.world_transforms()["t6"][:3, 3]
    proj = perspective_matrix(np.radians(40), 640 / 480, 0.05, 10.0)
    frame = [0]

    def draw(skinned: bool) -> None:
        frame[0] += 1  # a new camera each call: the renderer never skips an unchanged frame
        scene = view.build(env)
        if not skinned:
            scene.skins = []
        renderer.render(scene, look_at(c + [1.6, 0.3, 1.2 + 1e-4 * frame[0]], c), proj)
        renderer.read_pixels()

    repeat = 10 if quick else 40
    rigid = time_calls(lambda: draw(False), repeat)
    skinned = time_calls(lambda: draw(True), repeat)
    renderer.release()
    return Result("skin-draw", skinned.median_ms, skinned.p90_ms, rigid.median_ms, {"build_ms": round(build_ms, 1)})


CASES = [Case("skin-draw", _skin_draw, "a frame of the bent human, skinned vs the rigid segments")]
