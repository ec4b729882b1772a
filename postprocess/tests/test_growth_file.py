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
    # Passage 4 (stored: 2 and 4, counted from 1) has no contact history: the
    # contact figures show passage 1's, a note, exit 0; the file passes check.
    assert main(["figures", str(out), "--out", str(figs), "--pass", "4"]) == 0
    for name in ("rms_corrugation.png", "spectrogram.png", "profile_snapshots.png", "spectrum.png",
                 "loads.png", "levels.png", "level_growth.png"):
        assert (figs / name).stat().st_size > 1000, name
    assert not (figs / "wear_regimes.png").exists(), "Archard's law has one regime"
    assert main(["check", str(out)]) == 0


def test_wear_regimes_figure_of_a_law_with_regimes(tmp_path):
    # The wear map (four regimes): passes/wear_regime_share reads in xarray
    # with its regime names, each passage's shares sum to 1, and `figures`
    # draws wear_regimes.png; Archard's single regime draws none (above).
    out = tmp_path / "map.h5"
    subprocess.run(_command(out, "growth.passes=2", "growth.contact_history=[]", "wear.law=map"),
                   check=True, capture_output=True)
    with xr.open_dataset(out, engine="h5netcdf", group="passes") as ps:
        share = ps["wear_regime_share"]
        assert share.dims == ("pass", "wear_regime")
        assert ps["wear_regime"].attrs["flag_meanings"].split() == ["seizure", "mild", "severe", "fast_mild"]
        np.testing.assert_allclose(share.sum("wear_regime").values, 1.0, rtol=1e-12)
    figs = tmp_path / "figs"
    assert main(["figures", str(out), "--out", str(figs)]) == 0
    assert (figs / "wear_regimes.png").stat().st_size > 1000


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


MIX = """
[[traffic.mix]]
name = "fast"
share = 1.0

[[traffic.mix]]
name = "slow"
speed = 20.0
share = 1.0
"""


def test_mixed_traffic_classes_in_xarray_and_the_speeds_figure(tmp_path):
    # Two single-speed studies and their mix, written by the binary: the
    # traffic group and passes/traffic_class read in xarray, and `speeds`
    # finds the mix close to the share-weighted mean of the single speeds
    # (the linear regime; a few passages at a small m).
    config = tmp_path / "mix.toml"
    config.write_text((REPO / "configs" / "growth_fastsim.toml").read_text() + MIX)
    sets = ["growth.adaptive=false", "growth.traffic_scale=2e3", "growth.contact_history=[]"]
    runs = []
    for name, extra in (("fast", ["growth.passes=3"]), ("slow", ["growth.passes=3", "rolling.speed=20.0"])):
        out = tmp_path / f"{name}.h5"
        subprocess.run(_command(out, *sets, *extra), check=True, capture_output=True)
        runs.append(out)
    mix = tmp_path / "mix.h5"
    cmd = [BIN, "run", str(config), "-o", str(mix)]
    for s in COARSE + sets + ["growth.passes=6"]:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, capture_output=True)
    with xr.open_dataset(mix, engine="h5netcdf", group="traffic") as t:
        assert t["speed"].dims == ("class",)
        np.testing.assert_array_equal(t["speed"].values, [27.78, 20.0])
        np.testing.assert_allclose(t["share"].values, [0.5, 0.5])
        assert t.attrs["class_names"] == "fast slow"
    with xr.open_dataset(mix, engine="h5netcdf", group="passes") as ps:
        np.testing.assert_array_equal(ps["traffic_class"].values, [0, 1, 0, 1, 0, 1])
        assert ps["traffic_class"].attrs["flag_meanings"] == "fast slow"
    out = tmp_path / "speeds"
    assert main(["speeds", *map(str, runs), str(mix), "--out", str(out)]) == 0
    assert (out / "speeds.png").stat().st_size > 1000
    from corrugation_post.io import read_csv

    summary = {r["label"]: r for r in read_csv(out / "speeds_summary.csv")}
    assert float(summary["fast"]["peak_frequency_hz"]) > 0
    # Over the roughness band the mix's mean rate is within a tenth of the
    # spread of the single-speed rates of their share-weighted mean.
    rows = [r for r in read_csv(out / "speeds.csv") if r["label"] == "mix"]
    rate = np.array([float(r["growth_rate_db_per_1e5"]) for r in rows])
    pred = np.array([float(r["predicted_db_per_1e5"]) for r in rows])
    both = np.isfinite(rate) & np.isfinite(pred)
    assert both.sum() > 10
    singles = np.array([[float(r["growth_rate_db_per_1e5"]) for r in read_csv(out / "speeds.csv")
                         if r["label"] == name] for name in ("fast", "slow")])
    spread = np.nanmax(np.abs(singles[0] - singles[1]))
    assert np.max(np.abs(rate[both] - pred[both])) < 0.1 * spread
