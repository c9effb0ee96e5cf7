"""The lift's pictures (book §5.3.6 figures and §5.3.8 performance graphs) as one PNG, drawn with
Pillow (the project has no plotting library):

1. side view (forward vs up, m) of the hand paths of several lifts over the start posture's stick
   figure (light) and the detailed lift's end posture (dark), with the goal;
2. the torque ratios of shoulder, elbow and waist over time for one lift, its effective comfort
   limit (dashed), a strip naming the strategy of each step and a line where the waist joined;
3. the energy (cumulative ``sum |tau dtheta|``, J) of every lift over time.
"""

from __future__ import annotations

import io
from collections.abc import Sequence

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from jackpy.analysis.strength import joint_world_positions
from jackpy.analysis.ticks import nice_ticks
from jackpy.peabody.model import Figure
from jackpy.planning.lifting import ADDED_JOINT, AVAILABLE_TORQUE, PULL_BACK, REDUCING_MOMENT, LiftResult

PANEL_W, PANEL_H, MARGIN = 520, 520, 60
LOAD_COLOURS = [(31, 119, 180), (44, 160, 44), (255, 127, 14), (214, 39, 40), (148, 103, 189), (140, 86, 75)]
JOINT_COLOURS = {"shoulder": (31, 119, 180), "elbow": (255, 127, 14), "waist": (44, 160, 44)}
STRATEGY_COLOURS = {AVAILABLE_TORQUE: (120, 200, 120), REDUCING_MOMENT: (240, 200, 80),
                    PULL_BACK: (220, 90, 90), ADDED_JOINT: (120, 120, 220)}
_SKIP = ("eye", "index", "middle", "ring", "little", "thumb", "toes")


def _font(size: int) -> ImageFont.ImageFont:
    try:
        return ImageFont.load_default(size=size)
    except TypeError:  # Pillow without FreeType: the fixed bitmap font
        return ImageFont.load_default()


class Panel:
    """One chart: data limits ``lo``/``hi`` (2,) mapped into the box at ``origin`` (px)."""

    def __init__(self, draw: ImageDraw.ImageDraw, origin: tuple[int, int], lo: np.ndarray, hi: np.ndarray,
                 title: str, xlabel: str, ylabel: str, equal: bool = False) -> None:
        self.draw, self.ox, self.oy = draw, origin[0], origin[1]
        lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
        pad = (hi - lo) * 0.04 + 1e-9
        lo, hi = lo - pad, hi + pad
        self.w, self.h = PANEL_W - 1.4 * MARGIN, PANEL_H - 1.8 * MARGIN
        if equal:
            scale = max((hi[0] - lo[0]) / self.w, (hi[1] - lo[1]) / self.h)
            mid = (lo + hi) / 2
            lo = mid - scale * np.array([self.w, self.h]) / 2
            hi = mid + scale * np.array([self.w, self.h]) / 2
        self.lo, self.hi = lo, hi
        small, big = _font(13), _font(16)
        x0, y0 = self.ox + MARGIN, self.oy + 0.8 * MARGIN
        draw.rectangle([x0, y0, x0 + self.w, y0 + self.h], outline=(0, 0, 0))
        for t in nice_ticks(lo[0], hi[0]):
            px, _ = self.px(np.array([[t, lo[1]]]))[0]
            draw.line([px, y0 + self.h, px, y0 + self.h + 5], fill=(0, 0, 0))
            draw.text((px, y0 + self.h + 7), f"{round(t, 9) + 0.0:g}", fill=(0, 0, 0), font=small, anchor="ma")
        for t in nice_ticks(lo[1], hi[1]):
            _, py = self.px(np.array([[lo[0], t]]))[0]
            draw.line([x0 - 5, py, x0, py], fill=(0, 0, 0))
            draw.text((x0 - 8, py), f"{round(t, 9) + 0.0:g}", fill=(0, 0, 0), font=small, anchor="rm")
        draw.text((x0 + self.w / 2, self.oy + 10), title, fill=(0, 0, 0), font=big, anchor="ma")
        draw.text((x0 + self.w / 2, y0 + self.h + 28), xlabel, fill=(0, 0, 0), font=small, anchor="ma")
        draw.text((self.ox + 4, y0 - 16), ylabel, fill=(0, 0, 0), font=small, anchor="la")

    def px(self, p: np.ndarray) -> np.ndarray:
        """Data points (n, 2) -> pixel points (n, 2)."""
        p = np.atleast_2d(np.asarray(p, dtype=float))
        x = self.ox + MARGIN + (p[:, 0] - self.lo[0]) / (self.hi[0] - self.lo[0]) * self.w
        y = self.oy + 0.8 * MARGIN + self.h - (p[:, 1] - self.lo[1]) / (self.hi[1] - self.lo[1]) * self.h
        return np.column_stack([x, y])

    def line(self, p: np.ndarray, colour: tuple[int, int, int], width: int = 2, dashed: bool = False) -> None:
        pts = self.px(p)
        if dashed:
            for a, b in zip(pts[:-1:2], pts[1::2]):
                self.draw.line([tuple(a), tuple(b)], fill=colour, width=width)
        else:
            self.draw.line([tuple(q) for q in pts], fill=colour, width=width, joint="curve")

    def dot(self, p: np.ndarray, colour: tuple[int, int, int], r: int = 5) -> None:
        x, y = self.px(p)[0]
        self.draw.ellipse([x - r, y - r, x + r, y + r], fill=colour, outline=(0, 0, 0))

    def legend(self, items: Sequence[tuple[str, tuple[int, int, int]]], top: bool = True) -> None:
        font = _font(13)
        x = self.ox + MARGIN + 8
        y0 = self.oy + 0.8 * MARGIN + 8 if top else self.oy + 0.8 * MARGIN + self.h - 8 - 18 * len(items)
        for k, (text, colour) in enumerate(items):
            y = y0 + 18 * k
            self.draw.line([x, y + 7, x + 22, y + 7], fill=colour, width=3)
            self.draw.text((x + 28, y), text, fill=(0, 0, 0), font=font)


def _side(figure: Figure, points: np.ndarray) -> np.ndarray:
    """World points (n, 3) -> (forward, up) of the figure's side view, m."""
    forward = figure.location[:3, :3] @ np.array([0.0, 0.0, 1.0])
    forward[1] = 0.0
    forward /= max(np.linalg.norm(forward), 1e-12)
    p = np.atleast_2d(points)
    return np.column_stack([p @ forward, p[:, 1]])


def _bones(figure: Figure, q: np.ndarray, result: LiftResult) -> list[np.ndarray]:
    """World (2, 3) joint-to-parent-joint segments of the body (no fingers, eyes, toes; the root
    segment's joints hang from the root site; each wrist reaches to the grip of the lift's hand)."""
    kin = figure.kinematics()
    fk = kin.forward(q, figure.location)
    pos = joint_world_positions(figure, fk)
    into = {j.to_seg: j.name for j in figure.joints.values()}
    root = fk.segments[0] @ figure.site_location(*figure.root) if figure.root else fk.segments[0]
    out = []
    for j in figure.joints.values():
        if any(s in j.name for s in _SKIP):
            continue
        parent = into.get(j.from_seg)
        out.append(np.array([root[:3, 3] if parent is None else pos[parent], pos[j.name]]))
    wrist = f"{result.task.hand}_wrist"
    grip = result.frames[0].hand if np.array_equal(q, result.frames[0].q) else result.frames[-1].hand
    out.append(np.array([pos[wrist], grip]))
    return out


def lift_plot_png(figure: Figure, results: Sequence[LiftResult], detail: int = -1) -> bytes:
    """PNG bytes of the three panels (module docstring) for ``results`` (one per load, lifted by
    ``figure``); the ratio panel shows ``results[detail]``."""
    img = Image.new("RGB", (3 * PANEL_W, PANEL_H), (255, 255, 255))
    draw = ImageDraw.Draw(img)
    paths = [_side(figure, r.hand_path) for r in results]
    r = results[detail]
    first = [_side(figure, b) for b in _bones(figure, results[0].frames[0].q, results[0])]
    last = [_side(figure, b) for b in _bones(figure, r.frames[-1].q, r)]
    allp = np.vstack(paths + first + last + [_side(figure, x.task.goal) for x in results])
    side = Panel(draw, (0, 0), allp.min(axis=0), allp.max(axis=0), "Hand paths, side view",
                 "forward (m)", "up (m)", equal=True)
    for b in first:
        side.line(b, (200, 200, 200), width=4)
    for b in last:
        side.line(b, (90, 90, 90), width=3)
    items = []
    for k, (r, p) in enumerate(zip(results, paths)):
        c = LOAD_COLOURS[k % len(LOAD_COLOURS)]
        side.line(p, c)
        side.dot(_side(figure, r.task.goal), (0, 0, 0), r=4)
        if r.waist_added_at is not None:
            side.dot(p[r.waist_added_at], c, r=5)
        how = "reached" if r.reached else "stopped"
        items.append((f"{r.task.load_kg:.3g} kg, {how}" + (", +waist" if r.waist_added_at is not None else ""), c))
    side.legend(items + [("start posture", (200, 200, 200)), (f"end, {r.task.load_kg:.3g} kg", (90, 90, 90))],
                top=False)

    t = r.times
    ratios = r.joint_ratios()
    top = max(1.0, max(float(v.max()) for v in ratios.values()))
    rp = Panel(draw, (PANEL_W, 0), np.array([0.0, -0.08 * top]), np.array([max(t[-1], 1e-3), top]),
               f"Torque ratios, {r.task.load_kg:.3g} kg", "time (s)", "|torque| / strength")
    for name, v in ratios.items():
        rp.line(np.column_stack([t, v]), JOINT_COLOURS[name])
    rp.line(np.column_stack([np.linspace(0, t[-1], 60), np.interp(np.linspace(0, t[-1], 60), t,
                                                                  [f.limit for f in r.frames])]),
            (0, 0, 0), width=1, dashed=True)
    strip = rp.px(np.array([[0.0, -0.06 * top], [0.0, -0.02 * top]]))[:, 1]
    for a in range(1, len(t)):
        x0, x1 = rp.px(np.array([[t[a - 1], 0.0], [t[a], 0.0]]))[:, 0]
        draw.rectangle([x0, strip[1], max(x1, x0 + 1), strip[0]], fill=STRATEGY_COLOURS[r.frames[a].strategy])
    if r.waist_added_at is not None:
        ta = float(t[r.waist_added_at])
        rp.line(np.array([[ta, -0.08 * top], [ta, top]]), STRATEGY_COLOURS[ADDED_JOINT], width=2)
    rp.legend([(n, c) for n, c in JOINT_COLOURS.items()] + [("comfort limit", (0, 0, 0))]
              + [(s, c) for s, c in STRATEGY_COLOURS.items()])

    tmax = max(float(x.times[-1]) for x in results)
    emax = max(float(x.frames[-1].energy) for x in results)
    ep = Panel(draw, (2 * PANEL_W, 0), np.array([0.0, 0.0]), np.array([max(tmax, 1e-3), max(emax, 1e-3)]),
               "Energy", "time (s)", "sum |torque x angle| (J)")
    for k, x in enumerate(results):
        ep.line(np.column_stack([x.times, [f.energy for f in x.frames]]), LOAD_COLOURS[k % len(LOAD_COLOURS)])
    ep.legend([(f"{x.task.load_kg:.3g} kg", LOAD_COLOURS[k % len(LOAD_COLOURS)]) for k, x in enumerate(results)])
    buf = io.BytesIO()
    img.save(buf, format="PNG")
    return buf.getvalue()

