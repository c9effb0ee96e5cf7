"""Devices panel with split frames (no window): the simulator on a pty plays the shipped reach, the
panel's link connects, calibrates and starts, and headless workbench frames (:meth:`App.step`) drive
the human. With "Split frames" on, a frame's sensor step solves the spine and arms and the idle step
after the draw runs the owed loop steps; off, every frame is a full loop step. The palms follow their
sensors either way. A fault inside the idle step stops the drive and says so in the log. Frames and
steps are counted; nothing here asserts wall time."""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "behaviors"))  # the live drive's helpers
from flock_support import DRIVER_OPTIONS, EXAMPLE, PALMS, reach_fixture, reach_simulator  # noqa: F401

from jackpy.behaviors.base import BehaviorBase
from jackpy.devices.sensors import sensor_targets
from jackpy.errors import JackpyError
from jackpy.ui import session
from jackpy.ui.app import App
from jackpy.ui.panels.devices import DeviceLink, link_of


def make_app() -> App:
    """The workbench's default scene, its Devices link reading the reach's sensor configuration
    (the waist sensor's mount offset places the transmitter at calibration)."""
    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    link_of(app).sensors_path = str(EXAMPLE / "reach-sensors.json")
    return app


def connected(link: DeviceLink, sim) -> None:
    """Connect the link to the simulator, wait for every bird, calibrate and start driving."""
    assert link.connect(sim.paths[0], 4, **DRIVER_OPTIONS), link.error
    for b in range(1, 5):
        assert link.driver.store.wait(b, timeout=5.0) is not None
    assert link.calibrate() and link.start() and link.app.driving


def drive_reach(app: App, link: DeviceLink, motion) -> dict:
    """Play the reach, one workbench frame per new sample of the last bird, until 20 frames after
    its end. Each frame's palm error: the palm site's distance from the target of the samples the
    drive last consumed (kept by a driver listener, by bird and sequence number)."""
    drive = link.drive
    seen: dict[tuple[int, int], object] = {}
    link.driver.add_listener(lambda s: seen.__setitem__((s.bird, s.seq), s))
    fig = drive.loop.figure
    motion.play()
    worst, after_end, frames, idle_s = 0.0, 0, 0, 0.0
    for _ in range(20000):  # a cap, not a clock: the test ends on frames counted
        if link.driver.store.wait(4, after_seq=drive.consumed[4], timeout=1.0) is None:
            continue
        stats = app.step()
        assert app.driving, app.log[-3:]
        frames += 1
        idle_s += stats.idle_s
        used = {b: seen.get((b, q)) for b, q in drive.consumed.items()}
        if all(s is not None for s in used.values()):
            targets = sensor_targets(used, drive.calibration)
            worst = max(worst, *(np.linalg.norm(fig.site_world(*drive.sites[p])[:3, 3] - targets[p][:3, 3])
                                 for p in PALMS))
        if motion.done:
            after_end += 1
            if after_end >= 20:
                break
    assert motion.done, "the simulator played the whole recording"
    end = sensor_targets(link.driver.snapshot(), drive.calibration)  # the last frame, held
    last = max(np.linalg.norm(fig.site_world(*drive.sites[p])[:3, 3] - end[p][:3, 3]) for p in PALMS)
    return {"worst": worst, "last": last, "frames": frames, "idle_s": idle_s}


@pytest.mark.parametrize("split", [True, False], ids=["split", "full"])
def test_split_frames_from_the_panel_drive_the_reach(reach, split):
    app = make_app()
    link = link_of(app)
    assert link.split, "split frames are on by default"
    link.set_split(split)
    motion, sim = reach_simulator(reach)
    with sim:
        try:
            connected(link, sim)
            drive = link.drive
            assert drive.config.split is split
            got = drive_reach(app, link, motion)
            assert link.status().dropped == 0
        finally:
            link.disconnect()
    if split:  # sample frames solved the spine and arms; the loop's steps ran after the draw
        assert drive.split_frames > 0 and drive.idle_steps > 0, (drive.split_frames, drive.idle_steps)
        assert got["idle_s"] > 0.0  # counted in the frame stats
    else:
        assert drive.split_frames == 0 and drive.idle_steps == 0 and got["idle_s"] == 0.0
    # the palms followed their sensors within 2 cm on every frame and ended on them
    assert got["worst"] < 0.02, f"worst palm error {got['worst'] * 100:.2f} cm"
    assert got["last"] < 0.005, f"final palm error {got['last'] * 100:.2f} cm"


def test_split_frames_switch_while_connected(reach):
    app = make_app()
    link = link_of(app)
    _motion, sim = reach_simulator(reach)
    with sim:
        try:
            connected(link, sim)
            drive = link.drive
            assert drive.config.split
            for _ in range(8):
                app.step()
            assert drive.split_frames > 0
            link.set_split(False)  # the drive connected follows at once
            assert not drive.config.split and not link.split
            split_frames, idle_steps = drive.split_frames, drive.idle_steps
            for _ in range(4):
                app.step()
            assert (drive.split_frames, drive.idle_steps) == (split_frames, idle_steps)
            assert app.driving
        finally:
            link.disconnect()


@dataclass
class NoParams:
    """The failing behavior has no settings."""


class FailingBehavior(BehaviorBase):
    """A behavior whose update fails (as a behavior's bug would), once armed. The loop's full step
    runs it; a split frame runs only the arm behaviors, so with split frames the fault comes in
    the idle step after the draw."""

    name = "fault"
    order = 99

    def __init__(self) -> None:
        super().__init__(NoParams())
        self.armed = False

    def update(self, frame) -> None:
        if self.armed:
            raise JackpyError("injected behavior fault")


def test_a_fault_in_the_idle_step_stops_the_drive_and_is_logged(reach):
    app = make_app()
    link = link_of(app)
    _motion, sim = reach_simulator(reach)  # the neutral stance held: no step is taken
    with sim:
        try:
            connected(link, sim)
            drive = link.drive
            fault = FailingBehavior()
            drive.loop.behaviors.append(fault)
            for _ in range(8):  # a cap, not a clock: split frames and an idle step without the fault
                app.step()
                if drive.idle_steps:
                    break
            assert drive.idle_steps > 0 and drive.split_frames > 0
            fault.armed = True
            for _ in range(8):
                frames = drive.frames
                stats = app.step()
                if not app.driving:
                    break
            assert not app.driving and not link.driving
            assert app.log[-1] == "error: sensor drive stopped: injected behavior fault", app.log[-3:]
            # the frame's sensor step ended (a split frame) and the idle step after the draw raised
            assert drive.frames == frames + 1 and stats.idle_s > 0.0
            steps = drive.frames
            app.step()  # no longer driven: the document's own frame
            assert drive.frames == steps
        finally:
            link.disconnect()


def test_a_bad_sensor_configuration_is_logged_and_nothing_connects(tmp_path):
    app = make_app()
    link = link_of(app)
    link.sensors_path = str(tmp_path / "missing.json")
    assert not link.connect(str(tmp_path / "no-port"), 4, start_wait=0.5, rts_reset=None)
    assert "missing.json" in link.error and app.log[-1].startswith("error: connect")
    assert link.driver is None and app.sensor_drive is None
