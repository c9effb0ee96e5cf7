"""One module per motion kind; each registers its class with :func:`jackpy.motion.base.register`.
:func:`load_all` imports them (the timeline and the motion file call it)."""

from __future__ import annotations

import importlib
import pkgutil


def load_all() -> None:
    """Import every kind module of this package (registering the kinds)."""
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
        importlib.import_module(f"{__name__}.{info.name}")
