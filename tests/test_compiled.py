"""The kernels' registry: every numba kernel is declared, :func:`warm` compiles the signature the hot
path really calls (a frame never compiles one), and ``JACKPY_NO_JIT`` turns them all off."""

from __future__ import annotations

import importlib
import os
import subprocess
import sys
import threading

import pytest

from jackpy import compiled

pytestmark = pytest.mark.skipif(not compiled.AVAILABLE, reason="numba is not installed: nothing is compiled")


def _dispatchers() -> dict[int, str]:
    """Every numba dispatcher bound at module level in an imported jackpy module."""
    from numba.core.registry import CPUDispatcher

    for name in compiled.KERNEL_MODULES:
        importlib.import_module(name)
    import jackpy.body  # noqa: F401 - and what imports the kernels: the figure, the solver
    import jackpy.ik  # noqa: F401

    found = {}
    for mod_name, mod in list(sys.modules.items()):
        if mod_name.startswith("jackpy") and mod is not None:
            for attr, value in vars(mod).items():
                if isinstance(value, CPUDispatcher):
                    found[id(value)] = f"{mod_name}.{attr}"
    return found


def test_every_kernel_is_declared():
    found = _dispatchers()  # imports the kernels' modules first: each declares its kernels
    declared = {id(d) for _, d, _ in compiled.KERNELS}
    missing = [name for key, name in found.items() if key not in declared]
    assert not missing, f"numba kernels made outside jackpy.compiled.kernel: {missing}"
    assert sum(s is not None for _, _, s in compiled.KERNELS) >= 10


def test_warm_compiles_every_signature_and_a_second_warm_is_free():
    compiled.warm()
    for name, dispatcher, signature in compiled.KERNELS:
        if signature is not None:
            assert len(dispatcher.signatures) >= 1, name
    again = compiled.warm()
    assert (again.compiled, again.loaded) == (0, 0)


def test_the_hot_path_calls_the_declared_signatures():
    """After :func:`warm`, the IK robustness mix (three figures, every goal type, groups and cut rows,
    1-3 priority levels, bounded and book steps) and behavior-loop frames on the standard human
    compile nothing more: a frame never waits on numba."""
    from jackpy.behaviors import BehaviorLoop
    from jackpy.behaviors.anatomy import human_anatomy
    from jackpy.behaviors.manipulation import move_hand
    from jackpy.bench.cases_ik_robustness import run_mix
    from jackpy.body import make_human

    compiled.warm()
    before = {name: len(d.signatures) for name, d, s in compiled.KERNELS if s is not None}
    run_mix(24, seed=3, priority=True)
    run_mix(24, seed=4)
    fig = make_human("female", 50)
    loop = BehaviorLoop(fig, human_anatomy(fig))
    move_hand(loop, "right", fig.site_world("right_palm", "palm_centre")[:3, 3] + [0.1, 0.2, 0.3])
    for _ in range(3):
        loop.step()
    after = {name: len(d.signatures) for name, d, s in compiled.KERNELS if s is not None}
    assert after == before


def test_a_slow_warm_is_announced(monkeypatch):
    """A warm still compiling after ``ANNOUNCE_AFTER_S`` tells the user, once."""
    def _slow(n):  # pragma: no cover - compiled
        s = 0
        for i in range(n):
            s += i
        return s

    lines: list[str] = []
    done = threading.Event()
    monkeypatch.setattr(compiled, "ANNOUNCE_AFTER_S", 0.0)
    monkeypatch.setattr(compiled, "KERNELS", [])
    fresh = compiled.numba.njit(cache=False)(_slow)
    compiled.KERNELS.append(("test._slow", fresh, "(i8,)"))

    def announce(line: str) -> None:
        lines.append(line)
        done.set()

    report = compiled.warm(announce)
    done.wait(2.0)
    assert report.compiled == 1 and fresh(4) == 6
    assert len(lines) == 1 and "first run only" in lines[0]


def test_no_jit_turns_every_kernel_off():
    code = ("from jackpy import compiled; import jackpy.ik, jackpy.body; "
            "from jackpy.peabody.kinematics_jit import forward_kernel; from jackpy.ik import bounded_step; "
            "r = compiled.warm(); "
            "print(compiled.AVAILABLE, len(compiled.KERNELS), r.compiled, forward_kernel, bounded_step._box_step_compiled)")
    env = {**os.environ, "JACKPY_NO_JIT": "1"}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120, check=True)
    assert out.stdout.split() == ["False", "0", "0", "None", "None"]
