"""The mink rows' MuJoCo warnings are collected into the row, not printed into the bench table."""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco", reason="the bench extra (pip install jackpy[bench]) is not installed")
pytest.importorskip("mink", reason="the bench extra (pip install jackpy[bench]) is not installed")

import mujoco  # noqa: E402

from jackpy.bench import cases_mink  # noqa: E402


def test_loading_the_export_warns_into_the_row_and_the_handler_is_restored(capfd):
    before = mujoco.get_mju_user_warning()
    with cases_mink._mujoco_warnings() as warned:
        cases_mink.MinkSide(cases_mink.human())
    assert any("singular" in w for w in warned), warned  # the shoulder at gimbal lock (docs/robot-export.md)
    assert mujoco.get_mju_user_warning() is before
    out, err = capfd.readouterr()
    assert "WARNING" not in out + err  # MuJoCo prints it on stderr without the handler
