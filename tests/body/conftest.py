"""Shared figures for the body tests (built once per session; tests that pose them copy q back)."""

import pytest

from jackpy.body.human import make_human


@pytest.fixture(scope="session")
def female5():
    return make_human("female", 5)


@pytest.fixture(scope="session")
def male50():
    return make_human("male", 50)


@pytest.fixture(scope="session")
def male95():
    return make_human("male", 95)
