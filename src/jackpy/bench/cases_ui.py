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

The App runs with its frame budget (:mod:`jackpy.ui.frame_budget`, the workbench's default:
30 frames/s, adaptive quality); the baseline is the same drag with the budget's adaptation off (the
full quality and the document's 30 ms box, the frame loop before the budget), on a second App and
renderer in the same EGL context, in alternating blocks of frames so that both see the same load.
``fps`` is 1000 / the median frame; ``overruns`` counts frames whose solve took more than 1.2 times
its box, ``worst_overrun`` is the largest solve / box ratio (the promise: at most 1.2);
``solved`` the fraction of frames that solved (the last rung solves every other frame);
``levels`` how many frames ran on each rung of the quality ladder.
"""

from __future__ import annotations

import time

import numpy as np

from jackpy.bench.runner import Case, Result
from jackpy.ui.frame_budget import OVERRUN

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


class _Drag:
    """One App dragging the right hand on its own renderer (``ctx`` shared), frame by frame."""

    def __init__(self, ctx, with_cad: bool, adaptive: bool) -> None:
        from jackpy.ui.app import MOUSE_LEFT, PRESS, App, find_effectors
        from jackpy.render import offscreen_renderer
        from jackpy.ui.session import default_scene

        env, _ = default_scene()
        self.renderer = offscreen_renderer(*SIZE, samples=None, ctx=ctx)  # as the window's: automatic MSAA
        self.ctx = self.renderer.ctx
        self.screen_rb = self.ctx.renderbuffer(SIZE, 4)
        self.screen = self.ctx.framebuffer([self.screen_rb])
        app = self.app = App(env, self.renderer, SIZE)
        app.frame_budget.adaptive = adaptive
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
        self.path = [p0 + (p1 - p0) * (0.5 - 0.5 * np.cos(t)) for t in np.linspace(0.0, 4 * np.pi, 97)]
        self.k = 0
        self.frame_ms: list[float] = []
        self.solve: list[float] = []
        self.draw: list[float] = []
        self.levels: dict[int, int] = {}
        self.overruns = 0
        self.ratios: list[float] = []
        self.solved = 0

    def frame(self, record: bool = True) -> None:
        self.k = (self.k + 1) % len(self.path)
        self.app.on_cursor_pos(*self.path[self.k])
        t0 = time.perf_counter()
        stats = self.app.step()
        self.renderer.blit(self.screen)
        self.ctx.finish()
        ms = (time.perf_counter() - t0) * 1e3
        if not record:
            return
        self.frame_ms.append(ms)
        self.solve.append(stats.solve_s * 1e3)
        # the draw as the frame pays it: scene build and submit (App's draw_s) plus the GPU work
        # that finishes in the blit and ctx.finish()
        self.draw.append(ms - stats.solve_s * 1e3)
        self.levels[stats.level] = self.levels.get(stats.level, 0) + 1
        self.overruns += stats.solved and stats.solve_s > OVERRUN * stats.box_s
        if stats.solved and stats.box_s > 0:
            self.solved += 1
            self.ratios.append(stats.solve_s / stats.box_s)

    def figures(self, tag: str) -> dict:
        f = np.array(self.frame_ms)
        return {f"{tag}median_ms": float(np.median(f)), f"{tag}p90_ms": float(np.percentile(f, 90)),
                f"{tag}fps": 1e3 / float(np.median(f)), f"{tag}solve_ms": float(np.median(self.solve)),
                f"{tag}solve_p90_ms": float(np.percentile(self.solve, 90)),
                f"{tag}draw_ms": float(np.median(self.draw)), f"{tag}overruns": int(self.overruns),
                f"{tag}worst_overrun": round(max(self.ratios, default=0.0), 3),
                f"{tag}solved": round(self.solved / max(1, len(f)), 2), f"{tag}frames": len(f)}

    def release(self) -> None:
        self.screen.release()
        self.screen_rb.release()
        self.renderer.release()


def _interleaved(with_cad: bool, repeat: int, block: int = 10) -> tuple[_Drag, _Drag]:
    """The drag with the frame budget and without (adaptation off), in alternating blocks."""
    from jackpy.render import create_egl_context

    ctx = create_egl_context()
    ours, base = _Drag(ctx, with_cad, True), _Drag(ctx, with_cad, False)
    for d in (ours, base):
        for _ in range(5):
            d.frame(record=False)
    while len(ours.frame_ms) < repeat:
        for d in (ours, base):
            d.app.restart_frame_clock()  # the other App's block is not a frame of this one's budget
            for _ in range(2):
                d.frame(record=False)
            for _ in range(block):
                d.frame()
    return ours, base


def _ui_frame(quick: bool) -> Result:
    repeat = 30 if quick else 150
    ours, base = _interleaved(False, repeat)
    info = f"{ours.ctx.info.get('GL_RENDERER', '?').split(' (')[0]} {ours.renderer.samples}x"
    cad, _cad_base = _interleaved(True, repeat // 2)
    extra = {**ours.figures(""), **base.figures("fixed_"), "levels": dict(sorted(ours.levels.items())),
             "with_cad_ms": float(np.median(cad.frame_ms)), "with_cad_p90_ms": float(np.percentile(cad.frame_ms, 90)),
             "with_cad_fixed_ms": float(np.median(_cad_base.frame_ms)), "size": f"{SIZE[0]}x{SIZE[1]}",
             "renderer": info}
    result = Result("ui-frame", extra["median_ms"], extra["p90_ms"], extra["fixed_median_ms"], extra)
    for d in (ours, base, cad, _cad_base):
        d.release()
    return result


CASES = [Case("ui-frame", _ui_frame, "workbench frame (IK + offscreen draw) while dragging a hand with the "
                                      "frame budget (baseline: adaptation off), without / with a "
                                      "100k-triangle CAD object")]
