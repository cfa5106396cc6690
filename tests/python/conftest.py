"""Shared fixtures of the Python module's tests (issue 28): the repository's
scenes, and a temporary output folder per test."""
import os

import pytest

ROOT = os.environ.get("MFSD_SOURCE_DIR") or os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


@pytest.fixture
def configs():
    return os.path.join(ROOT, "configs")


@pytest.fixture
def out(tmp_path):
    return str(tmp_path / "run")
