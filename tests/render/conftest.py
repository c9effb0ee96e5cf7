"""One headless OpenGL context (moderngl over EGL) for the render tests of a module."""

import pytest


@pytest.fixture(scope="module")
def egl_context():
    import moderngl

    try:
        ctx = moderngl.create_standalone_context(require=330, backend="egl")
    except Exception as exc:  # no EGL device at all: nothing to render with
        pytest.skip(f"no EGL OpenGL context available: {exc}")
    yield ctx
    ctx.release()
