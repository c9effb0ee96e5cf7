"""Benchmark row ``ui-frame``: one workbench frame (behaviors + IK, then draw) while a hand is dragged.

The default scene (the 50th-percentile male, chair, work table) is drawn offscreen (EGL) at
1280x800 while the right hand is dragged back and forth through the App's own mouse handlers; each
timed call is one frame as the window does it: a cursor move, the time-boxed behavior frames
(``BehaviorLoop.step``), the draw, the blit of the image into a window-sized single-sample
framebuffer (standing in for ``ctx.screen``; no pixels are read back) and ``ctx.finish()`` (so GPU
time counts); ``draw_ms`` is that frame less the solve. The renderer is made as the window makes
it (``samples=None``: 4x MSAA on a GPU, none on a software rasteriser; ``renderer`` in the extras
says which). The row's median is the plain default scene; ``with_cad_*`` repeats it with a
100k-triangle CAD object in the scene.
"""

from __future__ import annotations

import time

import numpy as np

from jackpy.bench.runner import Case, Result, time_calls

SIZE = (1280, 800)


def _cad_object(triangles: int = 100_000):
    from jackpy.peabody import Mesh
    from jackpy.scene.cad import CADObject, ImportSettings
    from jackpy.render import uv_sphere

    rings = 250
    m = uv_sphere(0.4, rings=rings, sectors=triangles // (2 * rings))
    obj = CADObject("bench_cad", ImportSettings("bench_cad.stl"), Mesh(m.vertices, m.indices))
    obj.place(np.array([0.9, 0.9, 0.4]))
    return obj


def _frame_timer(with_cad: bool, repeat: int):
    from jackpy.ui.app import MOUSE_LEFT, PRESS, App, find_effectors
    from jackpy.render import offscreen_renderer
    from jackpy.ui.session import default_scene

    env, _ = default_scene()
    renderer = offscreen_renderer(*SIZE, samples=None)  # as the window's: automatic MSAA
    ctx = renderer.ctx
    screen_rb = ctx.renderbuffer(SIZE, 4)
    screen = ctx.framebuffer([screen_rb])
    app = App(env, renderer, SIZE)
    if with_cad:
        env.add(_cad_object())  # a CADObject: drawn translucent by its type
    app.camera.set_preset("front")
    app.step()
    fig = app.figure_of_interest()
    hand = fig.site_world(*find_effectors(fig)["right_hand"].split("."))[:3, 3]
    p0 = app.world_to_pixel(hand)
    p1 = app.world_to_pixel(hand + [0.25, 0.1, 0.0])
    app.on_cursor_pos(*p0)
    app.on_mouse_button(MOUSE_LEFT, PRESS, 0)
    path = [p0 + (p1 - p0) * (0.5 - 0.5 * np.cos(t)) for t in np.linspace(0.0, 4 * np.pi, 97)]
    state = {"k": 0, "solve": [], "draw": []}

    def frame() -> None:
        state["k"] = (state["k"] + 1) % len(path)
        app.on_cursor_pos(*path[state["k"]])
        t0 = time.perf_counter()
        stats = app.step()
        renderer.blit(screen)
        ctx.finish()
        state["solve"].append(stats.solve_s * 1e3)
        # the draw as the frame pays it: scene build and submit (App's draw_s) plus the GPU work
        # that finishes in the blit and ctx.finish()
        state["draw"].append((time.perf_counter() - t0 - stats.solve_s) * 1e3)

    timing = time_calls(frame, repeat=repeat, warmup=5)
    info = f"{ctx.info.get('GL_RENDERER', '?').split(' (')[0]} {renderer.samples}x"
    screen.release()
    screen_rb.release()
    renderer.release()
    return timing, float(np.median(state["solve"])), float(np.median(state["draw"])), info


def _ui_frame(quick: bool) -> Result:
    repeat = 30 if quick else 150
    plain, solve, draw, info = _frame_timer(False, repeat)
    cad, cad_solve, cad_draw, _ = _frame_timer(True, repeat)
    return Result("ui-frame", plain.median_ms, plain.p90_ms, None, {
        "solve_ms": solve, "draw_ms": draw, "with_cad_ms": cad.median_ms, "with_cad_p90_ms": cad.p90_ms,
        "with_cad_draw_ms": cad_draw, "size": f"{SIZE[0]}x{SIZE[1]}", "renderer": info})


CASES = [Case("ui-frame", _ui_frame, "workbench frame (IK + offscreen draw) while dragging a hand, "
                                      "without / with a 100k-triangle CAD object")]
