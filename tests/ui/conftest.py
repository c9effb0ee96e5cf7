"""The UI tests' fixtures (their helpers are in ``ui_support.py``: a module named ``conftest`` is
shadowed by other folders' conftest files when pytest is given several folders)."""

import pytest


@pytest.fixture(autouse=True)
def _user_home(tmp_path, monkeypatch):
    """Each test has its own ``$JACKPY_HOME`` (layout, recovery), never the user's ~/.jackpy."""
    monkeypatch.setenv("JACKPY_HOME", str(tmp_path / "jackpy_home"))
