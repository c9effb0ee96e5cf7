"""Devices panel: a Flock of Birds driving the human live (docs/devices.md).

Connect to a port or pyserial URL (a device path, a simulator's pty, ``socket://host:port``), with
a sensor configuration file (which bird is on which part, mount offsets, transmitter; empty: Jack's
four sensors), see the birds found with their parts, per-bird rate, dropped records and the
driver's state; calibrate with the operator standing in the figure's pose; start and stop driving
(each frame then runs one :meth:`~jackpy.behaviors.sensor_drive.SensorDrive.step`); record the raw
samples to a file.
"Split frames" (on by default, :attr:`DeviceLink.split`): a frame's sensor step solves the spine
and arms only, and the pelvis, balance, stepping and legs run after the draw in
:meth:`~jackpy.behaviors.sensor_drive.SensorDrive.idle`, in the time left before the next
workbench frame is due (:meth:`jackpy.ui.app.App.step`).

:class:`DeviceLink` holds that logic apart from ImGui (tests drive it without a window);
``jackpy --flock PORT`` connects one at start-up.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from imgui_bundle import imgui

from jackpy.errors import DeviceError, JackpyError
from jackpy.ui.panels import Panel

if TYPE_CHECKING:
    from jackpy.behaviors.sensor_drive import DriveStatus
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState


class DeviceLink:
    """The workbench's connection to a Flock: driver, sensor drive and recorder.

    Every action reports errors in the app's log (and in :attr:`error`) instead of raising.
    ``driver_options`` go to :class:`~jackpy.devices.flock.driver.FlockDriver` (e.g.
    ``rts_reset=None``, ``measurement_rate``). ``sensors_path``: a JSON sensor configuration
    (:func:`~jackpy.devices.sensors.load_sensor_config`) read at :meth:`connect`; empty: Jack's four
    sensors. ``split``: the drive's split frames
    (:class:`~jackpy.behaviors.sensor_drive.DriveConfig` ``split``; :meth:`set_split`).
    """

    def __init__(self, app: "App") -> None:
        self.app = app
        self.port = ""
        self.birds = 4
        self.record_path = "session.jsonl"
        self.sensors_path = ""
        self.split = True
        self.driver: Any = None
        self.drive: Any = None
        self.recorder: Any = None
        self.error: str | None = None

    # ------------------------------------------------------------------ state
    @property
    def connected(self) -> bool:
        return self.driver is not None

    @property
    def driving(self) -> bool:
        return self.app.driving and self.app.sensor_drive is self.drive and self.drive is not None

    def _fail(self, what: str, exc: Exception) -> bool:
        self.error = f"{what}: {exc}"
        self.app.info(f"error: {self.error}")
        return False

    def status(self) -> "DriveStatus | None":
        """The sensor drive's status (birds, rates, dropped ...), or None when not connected."""
        return self.drive.status() if self.drive is not None else None

    # ------------------------------------------------------------------ actions
    def connect(self, port: str, birds: int = 4, start_wait: float = 10.0, **driver_options: Any) -> bool:
        """Open ``port`` with ``birds`` sensors (waiting up to ``start_wait`` s for an answer) and
        attach a sensor drive to the human's behaviors (:attr:`sensors_path`'s configuration,
        split frames as :attr:`split`)."""
        from jackpy.behaviors.sensor_drive import DriveConfig, SensorDrive
        from jackpy.devices.flock.driver import FlockDriver
        from jackpy.devices.sensors import default_config, load_sensor_config

        self.disconnect()
        self.port, self.birds = port, int(birds)
        fig = self.app.figure_of_interest()
        loop = self.app.loops.get(fig.name) if fig is not None else None
        if loop is None:
            return self._fail(f"connect {port}", DeviceError("no standard human with behaviors to drive"))
        path = self.sensors_path.strip()
        try:
            sensors = load_sensor_config(Path(path).expanduser()) if path else default_config()
        except JackpyError as exc:
            return self._fail(f"connect {port}", exc)
        try:
            drv = FlockDriver(port, self.birds, **driver_options)
            drv.start(wait=start_wait)
        except (JackpyError, OSError, ValueError) as exc:
            return self._fail(f"connect {port}", exc)
        self.driver = drv
        drv.add_listener(self._record)
        self.drive = SensorDrive(loop, drv, DriveConfig(sensors=sensors, split=self.split))
        self.app.sensor_drive = self.drive
        self.error = None
        self.app.info(f"connected to {port}: birds {drv.birds}")
        return True

    def disconnect(self) -> None:
        """Stop driving and recording, close the port."""
        self.stop()
        self.stop_recording()
        if self.driver is not None:
            try:
                self.driver.stop()
            except (JackpyError, OSError) as exc:
                self._fail("disconnect", exc)
            self.app.info(f"disconnected from {self.port}")
        if self.app.sensor_drive is self.drive:
            self.app.sensor_drive = None
        self.driver = self.drive = None

    def set_split(self, on: bool) -> None:
        """Split frames on or off, for this link's next drive and the one connected (at once: the
        next frame follows the new setting; a split frame's owed loop step then runs as a full
        frame)."""
        self.split = bool(on)
        if self.drive is not None:
            self.drive.config.split = self.split

    def calibrate(self) -> bool:
        """Capture the transmitter placement and sensor offsets with the operator in the figure's pose."""
        if self.drive is None:
            return self._fail("calibrate", DeviceError("not connected"))
        try:
            self.drive.calibrate()
        except (JackpyError, ValueError) as exc:
            return self._fail("calibrate", exc)
        self.app.info("sensors calibrated")
        return True

    def start(self) -> bool:
        """Let the sensors drive the figure, one sensor-drive frame per workbench frame."""
        if self.drive is None or not self.drive.calibrated:
            return self._fail("start", DeviceError("calibrate first"))
        self.app.sensor_drive = self.drive
        self.app.driving = True
        self.app.info("sensor drive started")
        return True

    def stop(self) -> None:
        """The sensors stop driving; the figure stays where it is."""
        if self.driving:
            self.app.driving = False
            for loop in self.app.loops.values():
                loop.state.com_drag = None
            self.app.info("sensor drive stopped")

    def record(self, path: str | Path) -> bool:
        """Record every raw sample to ``path`` (JSON lines, see docs/devices.md)."""
        from jackpy.devices.recording import Recorder

        if self.driver is None:
            return self._fail("record", DeviceError("not connected"))
        self.stop_recording()
        try:
            self.recorder = Recorder(path, meta={"port": self.port, "birds": self.birds, "source": "jackpy workbench"})
        except (JackpyError, OSError) as exc:
            return self._fail(f"record {path}", exc)
        self.record_path = str(path)
        self.app.info(f"recording to {path}")
        return True

    def stop_recording(self) -> None:
        rec, self.recorder = self.recorder, None
        if rec is not None:
            rec.close()
            self.app.info(f"recording saved: {self.record_path}")

    def _record(self, sample: Any) -> None:  # on the driver's reader thread
        rec = self.recorder
        if rec is not None:
            rec.add(sample)


def link_of(app: "App") -> DeviceLink:
    """The app's device link (made on first use)."""
    link = getattr(app, "device_link", None)
    if link is None:
        link = DeviceLink(app)
        app.device_link = link  # type: ignore[attr-defined]
    return link


def draw(app: "App", ui: "UiState") -> None:
    link = link_of(app)
    vp = imgui.get_main_viewport()
    imgui.set_next_window_pos((vp.size.x - 620, 520), imgui.Cond_.first_use_ever)
    imgui.set_next_window_size((320, 300), imgui.Cond_.first_use_ever)
    visible, ui.open_panels["Devices"] = imgui.begin("Devices", ui.open_panels["Devices"])
    if visible:
        imgui.text("Flock of Birds")
        imgui.set_next_item_width(200)
        link.port = imgui.input_text("port or URL", link.port)[1]
        imgui.set_next_item_width(100)
        link.birds = max(1, min(14, imgui.input_int("birds", link.birds)[1]))
        imgui.set_next_item_width(200)
        link.sensors_path = imgui.input_text("sensors", link.sensors_path)[1]
        if imgui.is_item_hovered():
            imgui.set_tooltip("Sensor configuration (JSON, docs/devices.md), read at Connect;\n"
                              "empty: Jack's four sensors (1 waist, 2 neck, 3 left palm, 4 right palm).")
        changed, split = imgui.checkbox("Split frames", link.split)
        if changed:
            link.set_split(split)
        if imgui.is_item_hovered():
            imgui.set_tooltip("A frame's sensor step solves the spine and arms only; the pelvis, balance,\n"
                              "stepping and legs run after the draw, in the time left in the frame.")
        if not link.connected:
            if imgui.button("Connect") and link.port.strip():
                link.connect(link.port.strip(), link.birds)
        else:
            if imgui.button("Disconnect"):
                link.disconnect()
        st = link.status()
        if st is not None:
            imgui.text(f"state {st.state}, {'calibrated' if st.calibrated else 'not calibrated'}")
            for bird, part in sorted(st.birds.items()):
                rate = st.rates.get(bird)
                imgui.text(f"  bird {bird}: {part}, " + (f"{rate:.0f} Hz" if rate else "no data"))
            imgui.text(f"dropped records {st.dropped}, skipped samples {st.skipped}, frames {st.frames}")
            if st.last_error:
                imgui.text_colored((1.0, 0.4, 0.3, 1.0), st.last_error)
            if imgui.button("Calibrate"):
                link.calibrate()
            if imgui.is_item_hovered():
                imgui.set_tooltip("The operator stands in the figure's current pose.")
            imgui.same_line()
            if not link.driving:
                imgui.begin_disabled(not st.calibrated)
                if imgui.button("Start"):
                    link.start()
                imgui.end_disabled()
            elif imgui.button("Stop"):
                link.stop()
            imgui.separator()
            imgui.set_next_item_width(200)
            link.record_path = imgui.input_text("file", link.record_path)[1]
            if link.recorder is None:
                if imgui.button("Record") and link.record_path.strip():
                    link.record(Path(link.record_path.strip()).expanduser())
            elif imgui.button("Stop recording"):
                link.stop_recording()
        if link.error:
            imgui.text_wrapped(link.error)
    imgui.end()


PANEL = Panel("Devices", draw, order=70)
