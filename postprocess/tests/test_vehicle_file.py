"""A growth study with several wheels: the other wheels' patch histories
are subgroups ``contact/pass_NNNNN/wheel_K`` that xarray opens like the
leading wheel's group, and the layout check accepts the file."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest
import xarray as xr

from corrugation_post.schema import check_file

BIN = os.environ.get("CORRUGATION_BIN")
REPO = Path(__file__).resolve().parents[2]


@pytest.mark.skipif(not BIN, reason="CORRUGATION_BIN not set (scripts/test.sh sets it)")
def test_second_wheel_history(tmp_path):
    out = tmp_path / "bogie.h5"
    cfg = str(REPO / "configs" / "growth_fastsim.toml")
    done = subprocess.run([BIN, "run", cfg, "-o", str(out), "--set", "growth.passes=1",
                           "--set", "vehicle.wheels=[0.0, 2.5]", "--set", "growth.contact_history=[0]",
                           "--set", "dynamics.directions=vertical"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    lead = xr.open_dataset(out, engine="h5netcdf", group="contact/pass_00000")
    second = xr.open_dataset(out, engine="h5netcdf", group="contact/pass_00000/wheel_2")
    assert second["normal_force"].attrs["units"] == "N"
    assert second["normal_force"].shape == lead["normal_force"].shape
    assert abs(second["normal_force"] - lead["normal_force"]).max() > 1.0
    assert check_file(out) == []
