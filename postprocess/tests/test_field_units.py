"""The field's units in run files written by the real binary (issue 35): band
levels against the ISO 3095 limit, traffic in MGT and days, when each band
reaches the limit; the figures of them; ``figures`` and ``check`` on a
30-passage study whose contact history misses its last passage.

Needs ``$CORRUGATION_BIN`` (set by scripts/test.sh); skipped without it.
"""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from corrugation_post import figures, levels
from corrugation_post.cli import main
from corrugation_post.io import Run

BIN = os.environ.get("CORRUGATION_BIN")
REPO = Path(__file__).resolve().parents[2]
COARSE = ["contact.elements_x=6", "contact.elements_y=6", "rail.dx=5e-4", "rail.dy=1e-3",
          "passage.step_length=5e-4"]
TRAFFIC = ["traffic.axle_load=22.5e3", "traffic.axles_per_day=4000"]

pytestmark = pytest.mark.skipif(not BIN, reason="CORRUGATION_BIN not set (scripts/test.sh sets it)")


@pytest.fixture(scope="module")
def study(tmp_path_factory) -> tuple[Path, str]:
    """growth_fastsim.toml, coarse, 30 passages: its contact_history = [0, 149]
    keeps passage 1's history only. Returns the file and the run's stderr."""
    out = tmp_path_factory.mktemp("study") / "study.h5"
    cmd = [BIN, "run", str(REPO / "configs" / "growth_fastsim.toml"), "-o", str(out)]
    for s in COARSE + TRAFFIC + ["growth.passes=30", "growth.store_every=5"]:
        cmd += ["--set", s]
    done = subprocess.run(cmd, check=True, capture_output=True, text=True)
    return out, done.stderr


def test_levels_in_xarray_with_units(study):
    path, _ = study
    with xr.open_dataset(path, engine="h5netcdf", group="passes") as ps:
        assert ps["roughness_level"].dims == ("pass", "band")
        assert ps["band"].attrs["units"] == "m" and "wavelength" in ps["band"].attrs["long_name"]
        for name in ("roughness_level", "level_rate", "passages_to_limit", "limit_level", "traffic_mgt",
                     "traffic_days", "mgt_to_limit", "days_to_limit"):
            assert "units" in ps[name].attrs and "long_name" in ps[name].attrs, name
        band_mm = ps["band"].values * 1e3
        # Bands as EN 15610 labels them, longest first: a quarter of the
        # 120 mm stretch (25 mm) down.
        assert band_mm[0] == pytest.approx(25.0) and np.all(np.diff(band_mm) < 0)
        # ISO 3095: -5.6 dB at 2.5 cm, -8.0 at 1 cm.
        limit = ps["limit_level"].sel(band=0.025, method="nearest")
        assert float(limit) == -5.6 and ps["limit_level"].attrs["limit_name"] == "ISO 3095"
        assert float(ps["limit_level"].sel(band=0.010, method="nearest")) == -8.0
        level, rate = ps["roughness_level"].values, ps["level_rate"].values
        forced = ps["forced_band_wear"].values
        assert ps["forced_band_wear"].dims == ("pass", "band") and np.all(forced >= 0)
        lim = ps["limit_level"].values
        n = ps["passages_to_limit"].values
        lim2 = np.broadcast_to(lim, n.shape)
        # Consistent with the levels, rates and forced pattern (the forecast
        # the book states): A(n)^2 = A0^2 e^(2 s n) + f^2 ((e^(s n) - 1)/s)^2
        # reaches the limit's rms at n; a band that held no roughness of its
        # own at the start (-60 dB) and that the wear raised counts its rise
        # per wheel passage as a forcing. 0 above the limit.
        amp = lambda lv: 1e-6 * 10 ** (lv / 20)  # noqa: E731
        before = np.vstack([ps["initial_level"].values[None, :], level[:-1]])
        scale = ps["traffic_scale"].values[:, None]
        held = (ps["initial_level"].values[None, :] <= -60.0) & (rate >= 0)
        rise = np.where(before <= -120.0, np.sqrt(np.maximum(amp(level) ** 2 - (scale * forced) ** 2, 0.0)),
                        amp(before) * (10 ** (rate * scale / 20 / 1e5) - 1))
        a0 = amp(level)
        f = np.where(held, np.hypot(forced, rise / scale), forced)
        s = np.where(held, 0.0, rate * np.log(10) / 20 / 1e5)
        grows = np.isfinite(n) & (n > 0)
        assert grows.any()
        sn = s[grows] * n[grows]
        safe = np.where(np.abs(sn) < 1e-8, 1.0, s[grows])
        grown = np.where(np.abs(sn) < 1e-8, n[grows], np.expm1(sn) / safe)
        amp = np.hypot(a0[grows] * np.exp(sn), f[grows] * grown)
        at_n = 20 * np.log10(amp / 1e-6)
        np.testing.assert_allclose(at_n, lim2[grows], atol=1e-6)
        assert np.all(n[level >= lim] == 0)
        # Neither growing nor forced: never.
        assert np.all(np.isinf(n[(level < lim) & (s <= 0) & (f == 0)]))
        # Without a forced pattern the forecast is the straight line in dB.
        plain = grows & (f == 0) & ~held
        np.testing.assert_allclose(level[plain] + rate[plain] * n[plain] / 1e5, lim2[plain], atol=1e-9)
        # MGT and days: 22.5 t axles, 4000 a day.
        np.testing.assert_allclose(ps["traffic_mgt"].values, ps["traffic"].values * 22.5e-6, rtol=1e-12)
        np.testing.assert_allclose(ps["traffic_days"].values, ps["traffic"].values / 4000, rtol=1e-12)
        np.testing.assert_allclose(ps["days_to_limit"].values, n / 4000, rtol=1e-12)


def test_the_last_lines_say_when_a_band_reaches_the_limit(study):
    path, err = study
    tail = err.strip().splitlines()[-3:]
    text = "\n".join(tail)
    assert "ISO 3095 limit" in text, text
    with xr.open_dataset(path, engine="h5netcdf", group="passes") as ps:
        n = ps["passages_to_limit"].values[-1]
    if np.any(np.isfinite(n) & (n > 0)):
        assert "reaches the ISO 3095 limit" in text and "MGT" in text and " days" in text
        assert "at 4000 axles per day" in text
    else:
        assert "no band below the ISO 3095 limit grows towards it" in text


def test_figures_draw_what_is_stored_and_check_accepts_the_file(study, tmp_path, capsys):
    path, _ = study
    out = tmp_path / "figs"
    assert main(["figures", str(path), "--out", str(out)]) == 0
    captured = capsys.readouterr()
    assert "passage 30 has no contact history" in captured.err and "show passage 1" in captured.err
    # growth_fastsim.toml stores no patch fields: no traction snapshots, a note.
    assert "store_fields = false" in captured.err and "warning" not in captured.err
    for name in ("wear_map.png", "loads.png", "rms_corrugation.png", "spectrum.png", "levels.png",
                 "level_growth.png"):
        assert (out / name).stat().st_size > 1000, name
    assert main(["figures", str(path), "--out", str(out), "--levels-at", "1", "15", "30"]) == 0
    assert main(["figures", str(path), "--out", str(out), "--levels-at", "31"]) == 1
    assert "not in the run (passages 1-30)" in capsys.readouterr().err
    assert main(["check", str(path)]) == 0
    assert capsys.readouterr().out.strip().endswith("OK")


def test_titles_say_what_happens(study):
    path, _ = study
    run = Run.open(path)
    with run.pass_table() as ps:
        rms = ps["rms_corrugation"].values * 1e6
        traffic = ps["traffic"].values
    title = figures._rms_trend(rms, traffic)
    word = "grows" if rms[-1] > rms[0] * 1.01 else "falls" if rms[-1] < rms[0] * 0.99 else "holds"
    assert word in title and f"{rms[-1]:.3g}" in title


def test_crossings_are_found_between_passages():
    traffic = np.array([1.0, 2.0, 3.0])
    level = np.array([[0.0, 5.0], [2.0, 5.5], [4.0, 6.0]])
    cross = levels.crossings(traffic, np.array([-1.0, 5.0]), level, np.array([3.0, 4.5]))
    # Band 0 reaches 3 halfway between traffic 2 and 3; band 1 is above from the start.
    assert cross == {0: 2.5}
    assert levels.default_passes(30) == [1, 11, 20, 30]
