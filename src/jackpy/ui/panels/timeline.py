"""Timeline panel ([SH4] §4.3; [PB91] Fig. 5): the document's motions over time.

Time runs left to right in seconds (3 s visible at first; the span slider widens it). One track
per (figure, part); each motion is a bar from its start to its end tick with its weight function
(yellow) and velocity function (green) drawn over it as icons. Drag a bar to time-shift it, drag
its ends to retime it, right-click it to edit its times and weight, toggle or delete it; drag in the ruler to scrub. Play /
pause, loop, frame step, playback speed, and "set key" for a part of the figure at the current
time. Every edit is one document command, so Ctrl+Z undoes it. Playback shows baked postures at
the real frame rate (:class:`jackpy.motion.player.Player`), dropping frames rather than slowing
time. **Record** (at the chosen rate, Hz) turns what drives the figure of interest from now on (a
drag in the viewport, a live Flock session) into key tracks from the time cursor on; Stop puts
the take on the timeline as one undoable command (:class:`jackpy.motion.recorder.Recorder`). The
panel appears when the document has a timeline or a human to record.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from imgui_bundle import imgui

from jackpy.ui.panels import Panel

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState

TITLE = "Timeline"
TRACK_H = 22.0
RULER_H = 20.0
LABEL_W = 150.0
KEY_PARTS = ["hand.right", "hand.left", "foot.right", "foot.left", "pelvis", "com", "head", "eyes"]


def player_of(app: "App", ui: "UiState"):
    """The panel's player for the app's current document (made on first use)."""
    from jackpy.motion.player import Player

    state = ui.panel_state(TITLE, {"view0": 0.0, "drag": None, "key_part": 0})
    p = state.get("player")
    if p is None or p.doc is not app.doc:
        p = state["player"] = Player(app.doc)
    return p, state


def start_recording(app: "App", ui: "UiState", figure: str, rate: float | None = None):
    """Record button: pause playback and start a take of ``figure`` at ``rate`` Hz (default: the
    panel's rate) from the time cursor; returns the recorder."""
    from jackpy.motion.recorder import Recorder

    state = ui.panel_state(TITLE, {"view0": 0.0, "drag": None, "key_part": 0})
    player = state.get("player")
    if player is not None and player.playing:
        player.pause()
    app.doc.playing = False
    rec = state["recorder"] = Recorder(app.doc, figure, rate or state.get("rate", 10.0))
    rec.start()
    return rec


def stop_recording(app: "App", ui: "UiState") -> list:
    """Stop button: the take onto the timeline (one undo step); returns its key tracks."""
    state = ui.panel_state(TITLE, {"view0": 0.0, "drag": None, "key_part": 0})
    rec = state.pop("recorder", None)
    return rec.stop() if rec is not None else []


def _record_controls(app: "App", ui: "UiState", state: dict) -> None:
    rec = state.get("recorder")
    if rec is not None and rec.recording:
        if imgui.button("Stop"):
            stop_recording(app, ui)
            return
        imgui.same_line()
        imgui.text_colored(imgui.ImVec4(1.0, 0.3, 0.3, 1.0), f"REC {rec.figure} t = {rec.time:6.2f} s")
        return
    fig = app.figure_of_interest()
    if fig is None or fig.name not in app.doc.loops:
        return
    if imgui.button("Record"):
        start_recording(app, ui, fig.name)
    imgui.same_line()
    imgui.set_next_item_width(70)
    _, state["rate"] = imgui.slider_float("Hz", float(state.get("rate", 10.0)), 1.0, 60.0, "%.0f")


def tracks(timeline) -> list[tuple[str, str]]:
    """(figure, part) of every track, in first-use order (motions, then key tracks)."""
    out: list[tuple[str, str]] = []
    for m in timeline.motions:
        if (m.figure, m.part) not in out:
            out.append((m.figure, m.part))
    for b in timeline.timed:
        if (b.figure, b.part) not in out:
            out.append((b.figure, b.part))
    for k in timeline.tracks:
        if (k.figure, f"keys {k.part}") not in out:
            out.append((k.figure, f"keys {k.part}"))
    return out


def _curve(draw, x0: float, x1: float, y0: float, y1: float, fn, colour: int) -> None:
    from jackpy.motion.functions import velocity, weight_factor

    us = np.linspace(0.0, 1.0, 12)
    vals = [weight_factor(fn, u) if colour == _YELLOW else velocity(fn, u) / 2.0 for u in us]
    pts = [imgui.ImVec2(x0 + u * (x1 - x0), y1 - min(1.0, v) * (y1 - y0)) for u, v in zip(us, vals)]
    for a, b in zip(pts, pts[1:]):
        draw.add_line(a, b, colour, 1.5)


_YELLOW = 0xFF30D0E0
_GREEN = 0xFF40C040


def draw(app: "App", ui: "UiState") -> None:
    tl = app.doc.timeline
    if tl is None and not app.doc.loops:
        return
    vp = imgui.get_main_viewport()
    imgui.set_next_window_pos((270, vp.size.y - 330), imgui.Cond_.first_use_ever)
    imgui.set_next_window_size((vp.size.x - 560, 170), imgui.Cond_.first_use_ever)
    visible, ui.open_panels[TITLE] = imgui.begin(TITLE, ui.open_panels.get(TITLE, True))
    player, state = player_of(app, ui)
    rec = state.get("recorder")
    if rec is not None and rec.recording:
        rec.tick(imgui.get_io().delta_time)  # (a take runs on the window's clock, shown or not)
    elif tl is not None:
        player.update(imgui.get_io().delta_time)
    if visible:
        _record_controls(app, ui, state)
        tl = app.doc.timeline  # (a first take makes the timeline)
        if tl is not None and not (state.get("recorder") is not None and state["recorder"].recording):
            imgui.same_line()
            _toolbar(app, player, state)
            _tracks(app, player, state, tl)
    imgui.end()


def _toolbar(app: "App", player, state: dict) -> None:
    if imgui.button("Pause" if player.playing else "Play"):
        player.pause() if player.playing else player.play()
    imgui.same_line()
    _, player.loop = imgui.checkbox("loop", player.loop)
    imgui.same_line()
    if imgui.button("<"):
        player.step_frame(-1)
    imgui.same_line()
    if imgui.button(">"):
        player.step_frame(1)
    imgui.same_line()
    imgui.set_next_item_width(80)
    _, player.speed = imgui.slider_float("speed", player.speed, 0.1, 2.0)
    imgui.same_line()
    imgui.set_next_item_width(80)
    _, span = imgui.slider_float("span s", player.timeline.span, 0.5, 60.0)
    player.timeline.span = span
    imgui.same_line()
    baker = player.ensure_baker()
    imgui.text(f"t = {player.time:6.2f} s / {player.timeline.duration:.2f}  baked {len(baker.frames)}/{baker.n_frames}")
    fig = app.figure_of_interest()
    if fig is not None and fig.name in app.doc.loops:
        imgui.same_line()
        imgui.set_next_item_width(110)
        _, state["key_part"] = imgui.combo("##part", state["key_part"], KEY_PARTS)
        imgui.same_line()
        if imgui.button("set key"):
            player.set_key(fig.name, KEY_PARTS[state["key_part"]])


def _tracks(app: "App", player, state: dict, tl) -> None:
    draw = imgui.get_window_draw_list()
    origin = imgui.get_cursor_screen_pos()
    width = max(100.0, imgui.get_content_region_avail().x - LABEL_W)
    span = tl.span
    view0 = state["view0"]
    x_of = lambda t: origin.x + LABEL_W + (t - view0) / span * width  # noqa: E731
    t_of = lambda x: view0 + (x - origin.x - LABEL_W) / width * span  # noqa: E731
    # ruler: drag to scrub
    imgui.set_cursor_screen_pos(imgui.ImVec2(origin.x + LABEL_W, origin.y))
    imgui.invisible_button("##ruler", imgui.ImVec2(width, RULER_H))
    if imgui.is_item_active():
        if player.playing:
            player.pause()
        player.scrub(t_of(imgui.get_mouse_pos().x))
    for k in range(int(np.ceil(span)) + 1):
        t = np.floor(view0) + k
        x = x_of(t)
        draw.add_line(imgui.ImVec2(x, origin.y), imgui.ImVec2(x, origin.y + RULER_H), 0xFFA0A0A0)
        draw.add_text(imgui.ImVec2(x + 2, origin.y), 0xFFE0E0E0, f"{t:g}")
    rows = tracks(tl)
    y = origin.y + RULER_H
    for row, (fig, part) in enumerate(rows):
        draw.add_text(imgui.ImVec2(origin.x, y + 3), 0xFFE0E0E0, f"{fig} {part}")
        draw.add_line(imgui.ImVec2(origin.x + LABEL_W, y + TRACK_H), imgui.ImVec2(origin.x + LABEL_W + width, y + TRACK_H),
                      0x40FFFFFF)
        for mi, m in enumerate(tl.motions):
            if (m.figure, m.part) != (fig, part):
                continue
            x0, x1 = x_of(m.t0), x_of(m.t1)
            colour = 0xC0806040 if m.enabled else 0x60606060
            draw.add_rect_filled(imgui.ImVec2(x0, y + 2), imgui.ImVec2(x1, y + TRACK_H - 2), colour, 3.0)
            if m.weighted:
                _curve(draw, x0, x1, y + 3, y + TRACK_H - 3, m.weight_fn, _YELLOW)
            _curve(draw, x0, x1, y + 3, y + TRACK_H - 3, m.velocity_fn, _GREEN)
            _bar_handles(app, player, state, m, mi, x0, x1, y, width / span)
        for b in tl.timed:
            if (b.figure, b.part) == (fig, part):
                draw.add_rect_filled(imgui.ImVec2(x_of(b.t0), y + 6), imgui.ImVec2(x_of(b.t1), y + TRACK_H - 6),
                                     0xC0408080, 2.0)
        for k in tl.tracks:
            if (k.figure, f"keys {k.part}") == (fig, part):
                for t, _ in k.keys:
                    draw.add_circle_filled(imgui.ImVec2(x_of(t), y + TRACK_H / 2), 4.0, _YELLOW)
        y += TRACK_H
    # the time cursor
    xc = x_of(player.time)
    draw.add_line(imgui.ImVec2(xc, origin.y), imgui.ImVec2(xc, y), 0xFF3030FF, 2.0)
    imgui.set_cursor_screen_pos(imgui.ImVec2(origin.x, y + 4))
    imgui.dummy(imgui.ImVec2(1, 1))


def _bar_handles(app: "App", player, state: dict, m, mi: int, x0: float, x1: float, y: float, px_per_s: float) -> None:
    """Invisible buttons over a bar: its body shifts it, its ends retime it; right-click edits."""
    for which, (a, b) in (("start", (x0 - 4, x0 + 4)), ("end", (x1 - 4, x1 + 4)), ("body", (x0 + 4, x1 - 4))):
        if b - a < 2:
            continue
        imgui.set_cursor_screen_pos(imgui.ImVec2(a, y + 2))
        imgui.invisible_button(f"##{which}{mi}", imgui.ImVec2(b - a, TRACK_H - 4))
        if imgui.is_item_activated():
            app.doc.begin_edit()
            state["drag"] = (mi, which, m.t0, m.t1, imgui.get_mouse_pos().x)
        if imgui.is_item_active() and state["drag"] is not None and state["drag"][0] == mi:
            _, kind, t0, t1, mx = state["drag"]
            d = (imgui.get_mouse_pos().x - mx) / px_per_s
            if kind == "body":
                d = max(-t0, d)
                m.t0, m.t1 = t0 + d, t1 + d
            elif kind == "start":
                m.t0 = min(max(0.0, t0 + d), m.t1)
            else:
                m.t1 = max(m.t0, t1 + d)
        if imgui.is_item_deactivated() and state["drag"] is not None and state["drag"][0] == mi:
            state["drag"] = None
            app.doc.end_edit("shift motion" if which == "body" else "retime motion")
        if which == "body" and imgui.begin_popup_context_item(f"##menu{mi}"):
            imgui.text(f"{m.kind} motion {m.label}")
            for name, lo, hi in (("t0", 0.0, 600.0), ("t1", 0.0, 600.0), ("weight", 0.0, 100.0)):
                if name == "weight" and not m.weighted:
                    continue
                imgui.set_next_item_width(120)
                changed, v = imgui.drag_float(name, float(getattr(m, name)), 0.01, lo, hi)
                if imgui.is_item_activated():
                    app.doc.begin_edit()
                if changed:
                    setattr(m, name, v)
                    m.t1 = max(m.t0, m.t1)
                if imgui.is_item_deactivated():
                    app.doc.end_edit(f"edit motion {name}")
            if imgui.menu_item("disable" if m.enabled else "enable", "", False)[0]:
                player.toggle(m)
            if imgui.menu_item("delete", "", False)[0]:
                player.delete(m)
            imgui.end_popup()


PANEL = Panel(TITLE, draw, open=True, order=60)
