"""`corrugation spectrum` on a real config (growth_exact.toml over a 60 mm
stretch, two harmonics): the file reads with xarray and netCDF4 with the
names users' scripts rely on, its modes are sorted and self-consistent,
the figures are drawn; a config without a growth study is refused, and an
existing output is not replaced unasked."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import h5py
import numpy as np
import pytest
import xarray as xr

from corrugation_post.spectrum import figure

BIN = os.environ.get("CORRUGATION_BIN")
REPO = Path(__file__).resolve().parents[2]
SHORT = ["--set", "rail.x_max=0.06", "--set", "passage.end=0.06", "--set", "roughness.wavelength_max=0.06",
         "--set", "spectrum.wavelength_min=0.029", "--set", "spectrum.wavelength_max=0.061"]


@pytest.fixture(scope="module")
def spectrum_file(tmp_path_factory):
    if not BIN:
        pytest.skip("CORRUGATION_BIN not set (scripts/test.sh sets it)")
    out = tmp_path_factory.mktemp("spectrum") / "s.h5"
    cfg = str(REPO / "configs" / "growth_exact.toml")
    done = subprocess.run([BIN, "spectrum", cfg, "-o", str(out), *SHORT], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "fastest modes" in done.stderr
    return out


def test_spectrum_file_reads_with_the_contract_names(spectrum_file):
    ds = xr.open_dataset(spectrum_file, engine="h5netcdf", group="spectrum")
    for name in ("growth_rate", "wavelength", "frequency", "drift", "purity", "support_ratio"):
        assert ds[name].dims == ("mode",), name
        assert "units" in ds[name].attrs and "long_name" in ds[name].attrs, name
    assert ds.growth_rate.attrs["units"] == "dB/1e5 passages"
    assert ds.forced_wear.dims == ("wavelength",)
    assert ds.forced_wear.attrs["units"] == "m"
    # Two harmonics (60 and 30 mm) of a continuous track: two modes, fastest
    # first, each at its harmonic, f = V / lambda.
    assert ds.sizes["mode"] == 2
    rate = ds.growth_rate.values
    assert rate[0] >= rate[1]
    assert sorted(np.round(ds.wavelength.values * 1e3, 6)) == [30.0, 60.0]
    speed = float(ds.attrs["speed"])
    assert np.allclose(ds.frequency.values, speed / ds.wavelength.values, rtol=1e-12)
    assert (ds.purity.values > 0.99).all()
    # The forced pattern's wavelengths are the stretch's harmonics L/n; a
    # continuous track wears none beyond round-off.
    waves = ds.forced_wavelength.values
    assert abs(waves[0] - 0.06) < 1e-12 and abs(waves[1] - 0.03) < 1e-12
    assert ds.forced_wear.values.max() < 1e-6 * float(ds.mean_wear)
    # The map J: one class of four (both signs of two harmonics); its
    # diagonal gives the modes' rates (continuous track: no coupling).
    assert ds.jacobian_real.dims == ("harmonic", "source")
    diag = ds.diagonal_rate.values[ds.harmonic_wavenumber.values > 0]
    assert np.allclose(sorted(diag), sorted(rate), atol=1e-3)
    # Each mode's dual picks it out of its eigenvector (biorthogonal).
    v = ds.vector_real.values + 1j * ds.vector_imag.values
    d = ds.dual_real.values + 1j * ds.dual_imag.values
    assert np.allclose(d @ v.T, np.eye(ds.sizes["mode"]), atol=1e-9)
    # netCDF-C reads it too, with the modes' wavelength under its own name.
    import netCDF4

    with netCDF4.Dataset(spectrum_file) as nc:
        g = nc.groups["spectrum"]
        assert g.variables["wavelength"].dimensions == ("mode",)
        assert g.variables["forced_wear"].dimensions == ("wavelength",)
        assert "config" in nc.ncattrs()


def test_spectrum_figures(spectrum_file, tmp_path):
    paths = figure(spectrum_file, tmp_path)
    names = sorted(p.name for p in paths)
    assert names == ["spectrum_envelope.png", "spectrum_forced.png", "spectrum_modes.csv", "spectrum_modes.png"]
    assert all(p.stat().st_size > 0 for p in paths)


@pytest.mark.skipif(not BIN, reason="CORRUGATION_BIN not set (scripts/test.sh sets it)")
def test_spectrum_refuses_a_single_passage_and_keeps_an_existing_file(tmp_path):
    single = str(REPO / "configs" / "paper_normal_30mm.toml")
    done = subprocess.run([BIN, "spectrum", single, "-o", str(tmp_path / "x.h5")], capture_output=True, text=True)
    assert done.returncode == 2
    assert "[growth]" in done.stderr
    assert not (tmp_path / "x.h5").exists()
    kept = tmp_path / "kept.h5"
    kept.write_bytes(b"a checkpoint")
    cfg = str(REPO / "configs" / "growth_exact.toml")
    done = subprocess.run([BIN, "spectrum", cfg, "-o", str(kept)], capture_output=True, text=True)
    assert done.returncode == 2 and "--overwrite" in done.stderr
    assert kept.read_bytes() == b"a checkpoint"
    bad = subprocess.run([BIN, "spectrum", cfg, "-o", str(tmp_path / "y.h5"), "--set", "spectrum.classes=0"],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and "spectrum.classes" in bad.stderr


def test_the_forecast_group_reads_and_is_drawn(tmp_path):
    """Two Bloch classes put the 40 mm harmonic of the 120 mm supercell in
    the 40 mm one-third octave: its level now is the random roughness's own
    (1 um rms flat in wavenumber over 10-60 mm), its traffic to the ISO 3095
    limit where its level along the traffic axis crosses it, and the
    operator's units ride along."""
    if not BIN:
        pytest.skip("CORRUGATION_BIN not set (scripts/test.sh sets it)")
    out = tmp_path / "f.h5"
    cfg = str(REPO / "configs" / "growth_exact.toml")
    extra = ["--set", "spectrum.classes=2", "--set", "traffic.axle_load=20e3", "--set", "traffic.axles_per_day=5000"]
    done = subprocess.run([BIN, "spectrum", cfg, "-o", str(out), *SHORT, *extra], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "forecast against the ISO 3095 limit" in done.stderr, done.stderr
    fc = xr.open_dataset(out, engine="h5netcdf", group="forecast")
    assert fc.level_forecast.dims == ("band", "traffic")
    assert fc.level.attrs["units"] == "dB re 1 um"
    assert float(fc.attrs["tonnes_per_passage"]) == 20.0 and float(fc.attrs["axles_per_day"]) == 5000.0
    k = int(np.argmin(abs(fc.band.values - 0.04)))
    assert abs(fc.band.values[k] - 0.04) < 1e-12 and fc.lines.values[k] == 1
    width = 2 * np.pi / fc.band_lower.values[k] - 2 * np.pi / fc.band_upper.values[k]
    own = 10 * np.log10(width / (2 * np.pi / 0.01 - 2 * np.pi / 0.06))
    assert abs(fc.level.values[k] - own) < 1e-6, (fc.level.values[k], own)
    p, limit = float(fc.passages_to_limit.values[k]), float(fc.limit_level.values[k])
    levels = fc.level_forecast.values[k]
    traffic = fc.traffic.values
    if np.isfinite(p) and p > 0:
        assert (levels[traffic > p * 1.01] >= limit - 1e-9).all() and (levels[traffic < p * 0.99] < limit).all()
    else:
        assert p == 0 or (levels < limit).all()
    paths = [Path(p).name for p in figure(out, tmp_path / "figs")]
    assert "spectrum_forecast.png" in paths
    # The grinding forecast's figure where the file holds it (EN 13231-3's
    # bands inside the spectrum's wavelengths).
    with h5py.File(out, "r") as f:
        grinding = "forecast_grinding" in f
    assert ("spectrum_forecast_grinding.png" in paths) == grinding
