from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "tasks"


@pytest.fixture(scope="session")
def panel_scene() -> Path:
    return EXAMPLES / "panel" / "panel.json"


@pytest.fixture(scope="session")
def put_scene() -> Path:
    return EXAMPLES / "put" / "put.json"
