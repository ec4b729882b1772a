"""A growth study written by the real binary opens in xarray with named
dimensions, also as a checkpoint taken from a run killed mid-way, and its
growth figures are made.

Needs ``$CORRUGATION_BIN`` (set by scripts/test.sh); skipped without it.
"""

from __future__ import annotations

import os
import signal
import subprocess
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from corrugation_post.cli import main

BIN = os.environ.get("CORRUGATION_BIN")
REPO = Path(__file__).resolve().parents[2]
COARSE = ["contact.elements_x=6", "contact.elements_y=6", "rail.dx=5e-4", "rail.dy=1e-3",
          "passage.step_length=5e-4"]

pytestmark = pytest.mark.skipif(not BIN, reason="CORRUGATION_BIN not set (scripts/test.sh sets it)")


def _command(out: Path, *sets: str) -> list[str]:
    cmd = [BIN, "run", str(REPO / "configs" / "growth_fastsim.toml"), "-o", str(out)]
    for s in COARSE + list(sets):
        cmd += ["--set", s]
    return cmd


def _check_layout(path: Path, done: int):
    with xr.open_dataset(path, engine="h5netcdf", group="passes") as ps:
        assert ps["spectrum"].dims == ("pass", "wavelength")
        assert ps.sizes["pass"] == done
        assert np.all(np.isfinite(ps["spectrum"].values))
        assert ps["filtered_spectrum"].dims == ("pass", "wavelength")
        for name in ("traffic", "traffic_scale", "rms_corrugation", "update_ratio", "growth_rate"):
            assert ps[name].dims[0] == "pass", name
        # traffic is the running sum of the traffic scale
        np.testing.assert_allclose(np.cumsum(ps["traffic_scale"].values), ps["traffic"].values, rtol=1e-12)
    with xr.open_dataset(path, engine="h5netcdf", group="rail") as rail:
        assert rail["profile"].dims == ("pass", "y", "x")
        assert rail["wear"].dims == ("pass", "y", "x")
        assert rail["state"].dims == ("y", "x")
        assert rail.sizes["x"] == 240
    with xr.open_dataset(path, engine="h5netcdf") as root:
        assert int(root.attrs["passes_done"]) == done


def test_growth_study_opens_in_xarray_and_has_growth_figures(tmp_path):
    out = tmp_path / "growth.h5"
    subprocess.run(_command(out, "growth.passes=4", "growth.store_every=2", "growth.contact_history=[0]"),
                   check=True, capture_output=True)
    _check_layout(out, 4)
    with xr.open_dataset(out, engine="h5netcdf") as root:
        assert root.attrs["status"] == "complete"
    figs = tmp_path / "figs"
    assert main(["figures", str(out), "--out", str(figs), "--pass", "3"]) in (0, 1)
    for name in ("rms_corrugation.png", "spectrogram.png", "profile_snapshots.png", "spectrum.png"):
        assert (figs / name).stat().st_size > 1000, name


def test_a_checkpoint_of_a_killed_run_opens_in_xarray(tmp_path):
    out = tmp_path / "killed.h5"
    proc = subprocess.Popen(_command(out, "growth.passes=60", "growth.checkpoint_every=3"),
                            stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 120
    while not out.exists() and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.005)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert out.exists(), "no checkpoint before the kill"
    with xr.open_dataset(out, engine="h5netcdf") as root:
        done = int(root.attrs["passes_done"])
        assert root.attrs["status"] == "checkpoint", "the run was killed before it finished"
        assert int(root.attrs["passes_planned"]) == 60
    assert done % 3 == 0 and 0 < done < 60
    _check_layout(out, done)
