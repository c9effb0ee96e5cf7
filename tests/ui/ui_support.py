"""Helpers of the UI tests: offscreen renderers and running window tests in a child process."""

import os
import subprocess
import sys

import pytest


def offscreen_renderer_or_skip(width: int, height: int):
    """An offscreen (EGL) renderer, or skip the test with the reason when none can be made.

    Offscreen tests skip inside the window child process: that process must not make an EGL
    context before its GLX window (Mesa answers BadAccess).
    """
    if os.environ.get("JACKPY_WINDOW_CHILD"):
        pytest.skip("offscreen tests do not run in the window child")
    from jackpy.render import offscreen_renderer

    try:
        return offscreen_renderer(width, height)
    except Exception as exc:  # no EGL device
        pytest.skip(f"no offscreen OpenGL context: {exc}")


def in_child_process(request) -> bool:
    """Run this test in a fresh interpreter unless already there; True when the parent should stop.

    A GLX window cannot be created in a process that has made an EGL context (Mesa answers
    BadAccess), and offscreen tests in the same pytest run make EGL contexts.
    """
    if os.environ.get("JACKPY_WINDOW_CHILD"):
        return False
    env = dict(os.environ, JACKPY_WINDOW_CHILD="1")
    done = subprocess.run([sys.executable, "-m", "pytest", "-o", "addopts=", "-q", "-p", "no:cacheprovider",
                           request.node.nodeid],
                          cwd=request.config.rootpath, env=env, capture_output=True, text=True, timeout=240)
    assert done.returncode == 0 and " passed" in done.stdout, done.stdout[-4000:] + done.stderr[-2000:]
    return True
