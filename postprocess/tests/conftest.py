"""Test fixtures.

The run file under test is ``$CORRUGATION_RUN_FILE`` when set (a file written
by the real binary), else a small synthetic one written in ``tmp_path``.
Some tests always use synthetic files, because they need known values or
optional variables.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import matplotlib

matplotlib.use("Agg")

from synthetic_run import write_run  # noqa: E402  (tests/, on pytest's path)


ENV_VAR = "CORRUGATION_RUN_FILE"


@pytest.fixture
def synthetic_run(tmp_path) -> Path:
    """A synthetic run file with exactly the required content."""
    return write_run(tmp_path / "synthetic.h5")


@pytest.fixture
def run_file(tmp_path) -> Path:
    """The run file under test: $CORRUGATION_RUN_FILE, or a synthetic one."""
    env = os.environ.get(ENV_VAR)
    if env:
        path = Path(env)
        if not path.is_file():
            pytest.fail(f"{ENV_VAR}={env}: no such file")
        return path
    return write_run(tmp_path / "synthetic.h5")
