"""A sweep run and collected by the real binary opens in xarray with the
sweep's axes as named dimensions (with the keys' units), and its growth-rate
map is drawn against one and two axes.

Needs ``$CORRUGATION_BIN`` (set by scripts/test.sh); skipped without it.
"""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from corrugation_post.cli import main
from corrugation_post.io import read_csv

BIN = os.environ.get("CORRUGATION_BIN")
REPO = Path(__file__).resolve().parents[2]

pytestmark = pytest.mark.skipif(not BIN, reason="CORRUGATION_BIN not set (scripts/test.sh sets it)")

SPEC = """
base = "{base}"
output = "members"
set = ["contact.elements_x=6", "contact.elements_y=6", "rail.dx=5e-4", "rail.dy=1e-3", "passage.step_length=5e-4",
       "growth.passes=3", "growth.contact_history=[]"]

[[axis]]
key = "rolling.speed"
values = [22.22, 27.78, 33.33]

[[axis]]
key = "track.pad_stiffness"
values = [100e6, 500e6]
"""


@pytest.fixture(scope="module")
def collected(tmp_path_factory):
    d = tmp_path_factory.mktemp("sweep")
    spec = d / "spec.toml"
    spec.write_text(SPEC.format(base=REPO / "configs" / "growth_fastsim.toml"))
    subprocess.run([BIN, "sweep", "run", str(spec), "-j", "2"], check=True, capture_output=True)
    out = d / "sweep.h5"
    subprocess.run([BIN, "sweep", "collect", str(spec), "-o", str(out)], check=True, capture_output=True)
    return out


def test_collected_sweep_has_the_axes_as_dimensions(collected):
    with xr.open_dataset(collected, engine="h5netcdf") as ds:
        assert ds["growth_rate"].dims == ("rolling_speed", "track_pad_stiffness", "wavelength")
        assert ds["rolling_speed"].attrs["units"] == "m/s"
        assert ds["track_pad_stiffness"].attrs["units"] == "N/m"
        np.testing.assert_array_equal(ds["rolling_speed"].values, [22.22, 27.78, 33.33])
        assert ds["member_file"].sel(rolling_speed=27.78, track_pad_stiffness=500e6).item() == "member_0003.h5"
        assert int(ds["member"].sel(rolling_speed=33.33, track_pad_stiffness=100e6)) == 4
        assert np.all(ds["status"].values == 0)
        assert np.all(np.isfinite(ds["growth_rate"].values))
        for name in ("final_rms", "traffic", "cpu_seconds", "wear_per_passage", "initial_spectrum"):
            assert "units" in ds[name].attrs and "long_name" in ds[name].attrs, name
        # The pad changes the dynamics, so the growth (speed held).
        rate = ds["growth_rate"].sel(rolling_speed=27.78)
        assert float(np.max(np.abs(rate.isel(track_pad_stiffness=0) - rate.isel(track_pad_stiffness=1)))) > 0


def test_sweep_map_against_two_and_one_axes(collected, tmp_path):
    assert main(["sweep", str(collected), "--out", str(tmp_path / "two")]) == 0
    assert (tmp_path / "two" / "sweep_map.png").stat().st_size > 1000
    rows = read_csv(tmp_path / "two" / "sweep_map.csv")
    assert len(rows) == 6
    # The peak is a harmonic of the roughness (10-120 mm).
    assert all(0.0099 <= float(r["wavelength_m"]) <= 0.1201 for r in rows)
    assert main(["sweep", str(collected), "--y", "none", "--at", "track_pad_stiffness=1",
                 "--out", str(tmp_path / "one")]) == 0
    rows = read_csv(tmp_path / "one" / "sweep_map.csv")
    assert [float(r["rolling_speed"]) for r in rows] == [22.22, 27.78, 33.33]
    # At a given wavelength: the harmonic nearest it, the same for every member.
    assert main(["sweep", str(collected), "--wavelength", "0.031", "--out", str(tmp_path / "at")]) == 0
    rows = read_csv(tmp_path / "at" / "sweep_map.csv")
    with xr.open_dataset(collected) as ds:
        nearest = float(ds["wavelength"].sel(wavelength=0.031, method="nearest"))
    assert len(rows) == 6 and all(float(r["wavelength_m"]) == nearest for r in rows)
    assert abs(nearest - 0.031) < 0.005
    assert main(["sweep", str(collected), "--x", "rolling_speed", "--y", "rolling_speed",
                 "--out", str(tmp_path / "bad")]) == 2
    assert main(["sweep", str(collected), "--x", "nope", "--out", str(tmp_path / "bad")]) == 2


ZIPPED = """
base = "{base}"
output = "zipped"
set = ["contact.elements_x=6", "contact.elements_y=6", "rail.dx=5e-4", "rail.dy=1e-3", "passage.step_length=5e-4",
       "growth.passes=2", "growth.contact_history=[]"]

[[axis]]
key = "contact.fastsim_bound"
values = ["parabolic", "elliptic"]

[[axis]]
key = "rolling.speed"
values = [22.22, 27.78]
zip = true

[[axis]]
key = "dynamics.unsprung_mass"
values = [500, 700]
zip = true
"""


def test_string_and_zipped_axes(tmp_path):
    spec = tmp_path / "zipped.toml"
    spec.write_text(ZIPPED.format(base=REPO / "configs" / "growth_fastsim.toml"))
    subprocess.run([BIN, "sweep", "run", str(spec), "-j", "2"], check=True, capture_output=True)
    out = tmp_path / "zipped.h5"
    subprocess.run([BIN, "sweep", "collect", str(spec), "-o", str(out)], check=True, capture_output=True)
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        # A string axis as a string coordinate; the zipped axes share the
        # first one's dimension, the second a variable on it.
        assert ds["growth_rate"].dims == ("contact_fastsim_bound", "rolling_speed", "wavelength")
        assert list(ds["contact_fastsim_bound"].values) == ["parabolic", "elliptic"]
        assert ds["dynamics_unsprung_mass"].dims == ("rolling_speed",)
        np.testing.assert_array_equal(ds["dynamics_unsprung_mass"].values, [500.0, 700.0])
        assert ds["dynamics_unsprung_mass"].attrs["units"] == "kg"
        # member = bound index * 2 + speed index (row-major).
        assert int(ds["member"].sel(contact_fastsim_bound="elliptic", rolling_speed=22.22)) == 2
        # The bound changes the solution.
        a = ds["final_rms"].sel(contact_fastsim_bound="parabolic").values
        b = ds["final_rms"].sel(contact_fastsim_bound="elliptic").values
        assert np.all(a != b)
