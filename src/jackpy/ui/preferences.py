"""The user's preferences, kept per user (not per scene) in ``$JACKPY_HOME/preferences.json``
(default ``~/.jackpy``): the mouse preset, whether file dialogs are the desktop's own, and the
recent files of File → Open Recent.

The file is JSON, written atomically (:mod:`jackpy.atomic`); an unreadable or malformed file is
reported once in the log and replaced by the defaults at the next save, never a reason not to start.
"""

from __future__ import annotations

import json
import os
from dataclasses import asdict, dataclass, field, fields
from pathlib import Path

from jackpy.atomic import atomic_write_text
from jackpy.ui.camera import MOUSE_MAPPINGS

RECENT_MAX = 10
"""How many recent files File → Open Recent keeps."""
MOUSE_PRESET_LABELS = {"default": "jackpy", "blender": "Blender", "maya": "Maya"}
"""The Preferences window's name for each mouse preset of :data:`jackpy.ui.camera.MOUSE_MAPPINGS`."""


def jackpy_home() -> Path:
    """The per-user folder, ``$JACKPY_HOME`` (default ``~/.jackpy``)."""
    return Path(os.environ.get("JACKPY_HOME", Path.home() / ".jackpy"))


def preferences_path() -> Path:
    """``$JACKPY_HOME/preferences.json``."""
    return jackpy_home() / "preferences.json"


@dataclass
class Preferences:
    """Per-user preferences (see the module docstring)."""

    mouse_preset: str = "default"
    """A key of :data:`jackpy.ui.camera.MOUSE_MAPPINGS`: how empty-space drags move the camera."""
    native_dialogs: bool = True
    """Use the desktop's file dialogs (zenity, kdialog through portable-file-dialogs) when one is
    installed; off, or when none is: the workbench's own file browser."""
    recent: list[str] = field(default_factory=list)
    """Absolute paths of recently opened or saved scenes, newest first."""
    path: Path | None = field(default=None, repr=False, compare=False)
    """Where these were read from and are saved to (None: :func:`preferences_path` at save time)."""
    problem: str | None = field(default=None, repr=False, compare=False)
    """Why the file could not be read (shown once in the log), else None."""

    @classmethod
    def load(cls, path: Path | None = None) -> Preferences:
        """The preferences in ``path`` (default :func:`preferences_path`); defaults when there is
        no file; defaults with :attr:`problem` set when it cannot be read."""
        path = path or preferences_path()
        prefs = cls(path=path)
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except FileNotFoundError:
            return prefs
        except (OSError, ValueError) as exc:
            prefs.problem = f"warning: preferences {path} unreadable ({exc}); using defaults"
            return prefs
        if not isinstance(data, dict):
            prefs.problem = f"warning: preferences {path} is not a JSON object; using defaults"
            return prefs
        preset = data.get("mouse_preset")
        if isinstance(preset, str) and preset in MOUSE_MAPPINGS:
            prefs.mouse_preset = preset
        if isinstance(data.get("native_dialogs"), bool):
            prefs.native_dialogs = data["native_dialogs"]
        recent = data.get("recent")
        if isinstance(recent, list):
            prefs.recent = [r for r in recent if isinstance(r, str)][:RECENT_MAX]
        return prefs

    def save(self) -> None:
        """Write the preferences atomically (the folder is made when missing)."""
        path = self.path or preferences_path()
        path.parent.mkdir(parents=True, exist_ok=True)
        data = {f.name: getattr(self, f.name) for f in fields(self) if f.name not in ("path", "problem")}
        atomic_write_text(path, json.dumps(data, indent=2) + "\n")

    def add_recent(self, scene: str | os.PathLike[str]) -> None:
        """Put ``scene`` (made absolute) first in the recent files, once, and save."""
        p = str(Path(scene).expanduser().absolute())
        self.recent = [p] + [r for r in self.recent if r != p][: RECENT_MAX - 1]
        self.save()

    def forget_recent(self, scene: str | None = None) -> None:
        """Remove ``scene`` from the recent files (all of them when None), and save."""
        self.recent = [] if scene is None else [r for r in self.recent if r != scene]
        self.save()

    def as_dict(self) -> dict[str, object]:
        """The saved fields (for tests and the log)."""
        d = asdict(self)
        d.pop("path"), d.pop("problem")
        return d
