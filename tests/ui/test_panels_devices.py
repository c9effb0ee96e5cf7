"""Devices panel logic (no window): connect to the simulator on a pty, birds and rates, calibrate,
drive the human from the workbench frame step, record, disconnect; errors go to the log."""

import numpy as np

from jackpy.devices.flock.simulator import FlockSimulator
from jackpy.devices.recording import read_recording
from jackpy.ui import session
from jackpy.ui.app import App
from jackpy.ui.panels.devices import DeviceLink, link_of


def make_app() -> App:
    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    return app


def test_connect_calibrate_drive_record(tmp_path):
    app = make_app()
    fig = app.figure_of_interest()
    with FlockSimulator(4, rate=100.0, autoconfig_delay=0.05) as sim:
        link = link_of(app)
        assert link is link_of(app)
        assert link.connect(sim.paths[0], 4, rts_reset=None, autoconfig_wait=0.05, measurement_rate=100.0), link.error
        try:
            for b in range(1, 5):
                assert link.driver.store.wait(b, timeout=5.0) is not None
            st = link.status()
            assert st.state == "stream" and st.birds == {1: "pelvis", 2: "neck", 3: "left_palm", 4: "right_palm"}
            assert not link.start()  # not calibrated yet: refused, said in the log
            assert "calibrate first" in app.log[-1]
            assert link.record(tmp_path / "rec.jsonl")
            assert link.calibrate() and link.start() and app.driving
            q0 = fig.q.copy()
            frames = 0
            for _ in range(5000):  # a cap, not a clock: ends on frames that took fresh samples
                before = link.drive.frames
                app.step()
                frames += link.drive.frames - before
                if link.drive.frames >= 5 and set(link.status().rates) == {1, 2, 3, 4}:
                    break
            st = link.status()
            assert st.calibrated and st.frames >= 5 and st.dropped == 0
            assert all(r > 0 for r in st.rates.values())
            assert np.all(np.isfinite(fig.q)) and not np.array_equal(fig.q, q0)  # the sensors moved it
            link.stop()
            assert not app.driving
        finally:
            link.disconnect()
    assert link.driver is None and app.sensor_drive is None
    rec = read_recording(tmp_path / "rec.jsonl")
    assert rec.samples and set(rec.birds) <= {1, 2, 3, 4}


def test_connect_error_is_logged_and_scene_untouched(tmp_path):
    app = make_app()
    q = app.figure_of_interest().q.copy()
    link = DeviceLink(app)
    assert not link.connect(str(tmp_path / "no-such-port"), 4, start_wait=0.5, rts_reset=None,
                            reply_timeout=0.1)
    assert link.error and app.log[-1].startswith("error: connect")
    assert link.driver is None and app.sensor_drive is None and not app.driving
    assert np.array_equal(app.figure_of_interest().q, q)
    assert not link.calibrate() and not link.record(tmp_path / "r.jsonl")
