"""The docked layout, toasts and status bar in a real glfw window (Xvfb)."""

import os

import numpy as np
import pytest
from ui_support import in_child_process

if not os.environ.get("DISPLAY"):
    pytest.skip("window tests need an X display (run under xvfb-run, see scripts/test.sh)",
                allow_module_level=True)

from imgui_bundle import imgui  # noqa: E402

from jackpy.ui import session  # noqa: E402
from jackpy.ui.app import App, find_effectors  # noqa: E402
from jackpy.ui.scene_view import GoalPick  # noqa: E402
from jackpy.ui.status import residual_text  # noqa: E402
from jackpy.ui.window import Window  # noqa: E402


def window_rect(title):
    w = imgui.internal.find_window_by_name(title)
    return None if w is None or not w.active else (w.pos.x, w.pos.y, w.size.x, w.size.y)


def overlaps(a, r):
    ax, ay, aw, ah = a
    return ax < r.x + r.w - 1 and r.x < ax + aw - 1 and ay < r.y + r.h - 1 and r.y < ay + ah - 1


def test_default_layout_docks_every_panel_around_an_unobstructed_figure(request, tmp_path):
    if in_child_process(request):
        return
    env, _ = session.default_scene()
    app = App(env)
    win = Window(app, "jackpy layout", (1280, 800), visible=False)
    try:
        for title in win.ui.open_panels:  # panels opened later dock into their place too
            win.ui.open_panels[title] = True
        for _ in range(3):
            win.frame()
        r = win.view_rect
        assert 0.35 * 1280 < r.w < 0.8 * 1280 and 0.4 * 800 < r.h < 0.9 * 800
        drawn = [t for t in win.ui.open_panels if window_rect(t) is not None]
        assert {"Scene", "Goals", "Joints", "Log"} <= set(drawn)
        for title in drawn:
            assert not overlaps(window_rect(title), r), title
        fig = app.figure_of_interest()
        for w in fig.world_transforms().values():  # every segment of the figure lies in the view
            x, y = win.view_to_window(app.world_to_pixel(w[:3, 3]))
            assert r.x < x < r.x + r.w and r.y < y < r.y + r.h
        scene = window_rect("Scene")
        assert scene[0] + scene[2] <= r.x + 1  # the scene tree on the left
        assert window_rect("Goals")[0] >= r.x + r.w - 1 and window_rect("Log")[1] >= r.y + r.h - 1
    finally:
        win.close()
    ini = tmp_path / "jackpy_home" / "layout.ini"  # per user ($JACKPY_HOME), not the working folder
    assert ini.is_file() and "DockSpace" in ini.read_text()


def test_layout_is_restored_and_reset(request, tmp_path):
    if in_child_process(request):
        return
    env, _ = session.default_scene()
    ini = tmp_path / "layout.ini"
    win = Window(App(env), "jackpy layout", (1280, 800), visible=False, layout_file=ini)
    win.frame()
    default, left = win.view_rect, int(window_rect("Scene")[2])
    win.close()
    text = ini.read_text()
    narrower = text.replace(f"SizeRef={left},", f"SizeRef={left + 120},", 1)  # a wider scene tree
    assert narrower != text  # the left node's size is in the saved layout
    ini.write_text(narrower)
    win = Window(App(env), "jackpy layout", (1280, 800), visible=False, layout_file=ini)
    try:
        win.frame()
        assert abs(win.view_rect.w - default.w) > 30  # restored as saved, not rebuilt
        win.ui.reset_layout = True  # View > Reset layout
        for _ in range(3):
            win.frame()
        assert abs(win.view_rect.w - default.w) <= 1 and abs(win.view_rect.x - default.x) <= 1
    finally:
        win.close()


def test_errors_toast_and_status_bar_reports_an_unmet_goal(request):
    if in_child_process(request):
        return
    env, _ = session.default_scene()
    app = App(env)
    win = Window(app, "jackpy status", (1280, 800), visible=False)
    try:
        app.info("error: cannot read /nowhere/scene.env: no such file")
        app.info("saved scene.env")
        win.frame()
        assert [t.text for t in win.notifications.toasts] == ["error: cannot read /nowhere/scene.env: no such file"]
        assert window_rect("##toast0") is not None and overlaps(window_rect("##toast0"), win.view_rect)
        fig = app.figure_of_interest()
        goal = app.ensure_goal(fig, find_effectors(fig)["right_hand"], "position")
        far = goal.manip.copy()
        far[:3, 3] += [0.0, 0.0, 2.0]  # 2 m ahead: out of reach
        app.doc.move_goal(goal, far)
        app.select(GoalPick(goal.key))
        for _ in range(10):
            win.frame()
        text, met = residual_text(app, goal.key)
        assert not met and text.startswith("right hand: ") and text.endswith(" cm short")
        short = float(text.split(": ")[1].split(" cm")[0]) / 100
        hand = fig.site_world(*goal.site.split(".", 1))[:3, 3]
        assert abs(short - np.linalg.norm(far[:3, 3] - hand)) < 0.01
        assert win.rate.fps > 0
    finally:
        win.close()


def _without_windows(text, titles):
    """An imgui ini with the ``[Window][TITLE]`` sections of ``titles`` left out (a layout saved
    before those panels existed)."""
    blocks, keep = text.split("\n\n"), []
    for block in blocks:
        if not any(block.startswith(f"[Window][{t}]") for t in titles):
            keep.append(block)
    return "\n\n".join(keep)


def test_panels_an_old_saved_layout_does_not_know_dock_in_their_area(request, tmp_path):
    """A layout saved before a panel existed: the panel docks as a tab of its default area on
    first appearance (a new bottom panel too), never floating over the figure; a panel the
    user floated stays floating."""
    if in_child_process(request):
        return
    env, _ = session.default_scene()
    ini = tmp_path / "layout.ini"
    win = Window(App(env), "jackpy layout", (1280, 800), visible=False, layout_file=ini)
    win.frame()
    right = imgui.internal.find_window_by_name("Goals").dock_id
    bottom = imgui.internal.find_window_by_name("Log").dock_id
    win.close()
    new = ("Step editor", "Preferences", "Ergonomics")  # right, right, bottom by default
    old = _without_windows(ini.read_text(), new)
    old = old.replace("[Window][Script]\nCollapsed=0\nDockId=0x00000006",  # the user floated it
                      "[Window][Script]\nPos=500,300\nSize=200,150\nCollapsed=0")
    assert all(f"[Window][{t}]" not in old for t in new) and "[Window][Script]" in old
    ini.write_text(old)
    win = Window(App(env), "jackpy layout", (1280, 800), visible=False, layout_file=ini)
    try:
        for title in (*new, "Script"):
            win.ui.open_panels[title] = True
        for _ in range(3):
            win.frame()
        r = win.view_rect
        for title, node in zip(new, (right, right, bottom)):
            w = imgui.internal.find_window_by_name(title)
            assert w is not None and w.dock_id == node, title  # a tab beside its area's panels
            if window_rect(title) is not None:  # (the tab shown)
                assert not overlaps(window_rect(title), r), title
        assert imgui.internal.find_window_by_name("Script").dock_id == 0  # floated by the user: kept
    finally:
        win.close()
    assert "[Window][Step editor]" in ini.read_text()  # known from now on


def test_a_whole_area_an_old_layout_lacks_is_split_off_the_view(request, tmp_path):
    """No panel of the bottom area in the saved layout: they dock together in a new node below
    the 3-D view (none floats over it)."""
    if in_child_process(request):
        return
    env, _ = session.default_scene()
    ini = tmp_path / "layout.ini"
    win = Window(App(env), "jackpy layout", (1280, 800), visible=False, layout_file=ini)
    win.frame()
    win.close()
    bottom = ("Timeline", "Log", "Ergonomics")
    ini.write_text(_without_windows(ini.read_text(), bottom))
    win = Window(App(env), "jackpy layout", (1280, 800), visible=False, layout_file=ini)
    try:
        for title in ("Log", "Ergonomics"):
            win.ui.open_panels[title] = True
        for _ in range(3):
            win.frame()
        r = win.view_rect
        nodes = {imgui.internal.find_window_by_name(t).dock_id for t in ("Log", "Ergonomics")}
        assert len(nodes) == 1 and 0 not in nodes  # one new node, shared
        log = window_rect("Log") or window_rect("Ergonomics")
        assert log[1] >= r.y + r.h - 1 and not overlaps(log, r)
    finally:
        win.close()
