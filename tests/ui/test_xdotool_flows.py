"""Issue 21's acceptance as a user does it: the real ``jackpy open SCENE`` process under Xvfb,
driven by xdotool's X events (keys and mouse through the X server, not our callbacks), observed
through the window title (``*`` = unsaved changes) and screenshots of the X display.

Press 3: side view (1 returns to the front); drag the figure, click in a panel, Ctrl+Z: the drag
is undone; Ctrl+Q with unsaved changes: the prompt (the screen dims), Escape = Cancel: the window
stays; kill -9, ``jackpy open SCENE`` again: recovery is offered, Enter recovers it (the title
then marks the recovered, unsaved work).
"""

import os
import shutil
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

if not os.environ.get("DISPLAY") or shutil.which("xdotool") is None:
    pytest.skip("needs an X display and xdotool (scripts/install-system-deps.sh)", allow_module_level=True)

from PIL import ImageGrab  # noqa: E402

from jackpy.ui import session  # noqa: E402
from jackpy.ui.app import App  # noqa: E402

W, H = 1280, 800


def xdo(*args: str) -> str:
    return subprocess.run(["xdotool", *args], capture_output=True, text=True, timeout=60).stdout.strip()


def wait_for(predicate, what: str, timeout: float = 90.0, every: float = 0.25):
    t_end = time.monotonic() + timeout
    while time.monotonic() < t_end:
        value = predicate()
        if value is not None and value is not False:
            return value
        time.sleep(every)
    raise AssertionError(f"timed out waiting for {what}")


class Workbench:
    """A ``jackpy open`` process and its X window."""

    def __init__(self, scene, home):
        env = dict(os.environ, JACKPY_HOME=str(home))
        env.pop("JACKPY_WINDOW_CHILD", None)
        self.proc = subprocess.Popen([sys.executable, "-m", "jackpy", "open", str(scene)], env=env,
                                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        self.wid = wait_for(lambda: self._window(scene.name), "the window")
        xdo("windowmove", "--sync", self.wid, "0", "0")
        xdo("windowfocus", "--sync", self.wid)
        time.sleep(2.0)

    def _window(self, name):
        assert self.proc.poll() is None, self.proc.stdout.read().decode()[-3000:]
        found = xdo("search", "--name", f"{name} \u2014 jackpy").split()
        return found[0] if found else None

    @property
    def title(self) -> str:
        return xdo("getwindowname", self.wid)

    def shot(self, settle: float = 1.5) -> np.ndarray:
        """The 3-D view's middle (no panels), as float RGB, once the frame stopped changing."""
        time.sleep(settle)

        def grab():
            img = np.asarray(ImageGrab.grab(xdisplay=os.environ["DISPLAY"]).convert("RGB"), dtype=float)
            view = img[60:560, 260:920]
            return view if view.std() > 5.0 else None  # the 3-D view drawn, not the clear colour

        last = [wait_for(grab, "the 3-D view", timeout=60, every=0.5)]

        def still():  # two grabs 0.5 s apart alike: the still frame (full quality), not a moving one
            now = grab()
            same = now is not None and differs(now, last[0]) < 0.05
            last[0] = now if now is not None else last[0]
            return now if same else None

        return wait_for(still, "a still 3-D view", timeout=60, every=0.5)

    def key(self, *keys: str) -> None:
        xdo("windowfocus", "--sync", self.wid)
        for k in keys:
            xdo("key", "--window", self.wid, "--delay", "60", k)

    def drag(self, x0, y0, dx, dy) -> None:
        xdo("mousemove", "--sync", str(x0), str(y0))
        time.sleep(0.5)
        xdo("mousedown", "1")
        time.sleep(0.5)  # the press is a frame of its own (pick, then the operator)
        for t in np.linspace(0.0, 1.0, 8)[1:]:
            xdo("mousemove", "--sync", str(int(x0 + t * dx)), str(int(y0 + t * dy)))
            time.sleep(0.2)
        time.sleep(0.3)
        xdo("mouseup", "1")

    def click(self, x, y) -> None:
        xdo("mousemove", "--sync", str(x), str(y))
        time.sleep(0.2)
        xdo("click", "1")

    def kill(self) -> None:
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGKILL)
        self.proc.wait(timeout=30)


def differs(a: np.ndarray, b: np.ndarray) -> float:
    """Mean absolute difference of two shots, grey levels."""
    return float(np.abs(a - b).mean())


def figure_chest(shot: np.ndarray) -> tuple[int, int]:
    """Window coordinates of the figure's chest (its skin-coloured pixels' middle column, 30 % down
    from the top of the head): a torso segment, so a drag there moves the whole figure."""
    r, g, b = shot[..., 0], shot[..., 1], shot[..., 2]
    skin = (r > 150) & (r > g + 15) & (g > b + 10)
    ys, xs = np.nonzero(skin)
    assert len(xs) > 200, "no figure in the 3-D view"
    return int(np.median(xs)) + 260, int(ys.min() + 0.3 * (ys.max() - ys.min())) + 60


@pytest.fixture
def scene(tmp_path):
    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    app.settings.autosave_s = 4.0  # saved with the scene: the crash below finds a fresh autosave
    path = tmp_path / "scene.env"
    session.save_session(app, path)
    return path


def until(wb, condition, what: str, timeout: float = 45.0) -> np.ndarray:
    """The first shot (taken every half second) for which ``condition(shot)`` holds."""
    return wait_for(lambda: (lambda a: a if condition(a) else None)(wb.shot(0.5)), what, timeout=timeout, every=0.0)


def test_views_undo_quit_prompt_and_crash_recovery(scene, tmp_path):
    home = tmp_path / "home"
    wb = Workbench(scene, home)
    try:
        assert wb.title == "scene.env \u2014 jackpy"
        front = wb.shot()
        wb.key("3")
        side = until(wb, lambda a: differs(front, a) > 2.0, "the side view")
        wb.key("1")
        until(wb, lambda a: differs(front, a) < 0.25 * differs(side, a), "the front view again")

        x, y = figure_chest(front)
        wb.drag(x, y, -120, 0)  # moves the whole figure
        assert wait_for(lambda: wb.title.startswith("*"), "the modified marker", timeout=30)
        moved = until(wb, lambda a: differs(front, a) > 1.0, "the figure moved")
        wb.click(640, 700)  # inside the Log panel: the keys must still work
        wb.key("ctrl+z")
        until(wb, lambda a: differs(front, a) < 0.5 * differs(moved, a), "the drag undone")

        wb.drag(x, y, -120, 0)  # modify again; the recovery autosave (every 4 s) catches it
        dragged = until(wb, lambda a: differs(moved, a) < 0.5 * differs(front, a), "the figure dragged again")
        wb.key("ctrl+q")
        until(wb, lambda a: differs(dragged, a) > 3.0, "the quit prompt (the modal dims the view)")
        assert wb.proc.poll() is None
        wb.key("Escape")  # Cancel
        until(wb, lambda a: differs(dragged, a) < 1.0, "the prompt gone")
        time.sleep(1.0)
        assert wb.proc.poll() is None  # Cancel kept the window
        recovery = home / "recovery" / session.recovery_path(scene).name  # the scene's own recovery file
        since = time.time()
        wait_for(lambda: recovery.is_file() and recovery.stat().st_mtime > since + 0.5, "an autosave after the drag",
                 timeout=60)
    finally:
        wb.kill()  # kill -9: no clean exit, the recovery file stays
    assert recovery.is_file()
    seen = home / "seen"  # a copy beside the recovery folder: its relative references still resolve
    shutil.copytree(recovery.parent, seen)

    wb = Workbench(scene, home)
    try:
        assert wb.title == "scene.env \u2014 jackpy"  # the saved scene, with the offer over it
        offer = wb.shot()
        wb.key("Return")  # Enter = Recover (the answer that loses nothing)
        assert wait_for(lambda: wb.title == "*scene.env \u2014 jackpy", "the recovered work", timeout=30)
        recovered = wb.shot(3.0)
        assert differs(recovered, offer) > 1.0  # the prompt closed (the view no longer dimmed)
        original = _figure_places(scene)
        wb.key("ctrl+s")  # the recovered work saved over the scene it is the autosave of
        assert wait_for(lambda: wb.title == "scene.env — jackpy", "the save", timeout=30)
    finally:
        wb.kill()
    saved, autosaved = _figure_places(scene), _figure_places(seen / recovery.name)
    assert saved.keys() == autosaved.keys() == original.keys()
    moved = [n for n in saved if not np.allclose(original[n], autosaved[n], atol=1e-4)]
    assert moved  # the autosave holds the drag ...
    for n in saved:  # ... and the work restored is exactly what was autosaved
        assert np.allclose(saved[n], autosaved[n], atol=1e-6), n


def _figure_places(path) -> dict[str, np.ndarray]:
    """World location (4x4, flattened) and displacements of every figure with joints in the session."""
    from jackpy.document import session as doc_session

    library = os.environ.get("JACKPY_LIBRARY")
    os.environ["JACKPY_LIBRARY"] = str(session.default_scene()[1])  # where the default scene's figures are
    try:
        env, _ = doc_session.load_session(path)
    finally:
        if library is None:
            del os.environ["JACKPY_LIBRARY"]
        else:
            os.environ["JACKPY_LIBRARY"] = library
    return {n: np.concatenate([f.location.ravel(), f.q]) for n, f in env.figures.items() if f.joints}
