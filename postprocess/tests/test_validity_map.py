"""The validity map of the Hertz normal contact from a manifest of real
growth passages: both models' wear less their smooth-rail wear compared per
corrugation, failed runs reported with their error."""

from __future__ import annotations

import math
import os
import subprocess
from pathlib import Path

import pytest

from corrugation_post.validity_map import chart, evaluate, markdown

BIN = os.environ.get("CORRUGATION_BIN")
REPO = Path(__file__).resolve().parents[2]


@pytest.mark.skipif(not BIN, reason="CORRUGATION_BIN not set (scripts/test.sh sets it)")
def test_validity_map_compares_hertz_and_profile(tmp_path):
    rows = []
    cases = [(0.03, 0.0), (0.03, 1e-5), (0.015, 1e-5)]
    for wavelength, amplitude in cases:
        for normal in ("hertz", "profile"):
            f = tmp_path / f"{wavelength}_{amplitude}_{normal}.h5"
            # The 15 mm Hertz run is made to fail (a bad key value).
            bad = wavelength == 0.015 and normal == "hertz"
            cmd = [BIN, "run", str(REPO / "configs" / "growth_exact.toml"), "-o", str(f),
                   "--set", "growth.passes=1", "--set", "growth.adaptive=false",
                   "--set", "growth.contact_history=[0]", "--set", "roughness.kind=harmonics",
                   "--set", f"roughness.harmonics=[{{amplitude = {amplitude}, wavelength = {wavelength}}}]",
                   "--set", "rail.x_max=0.06", "--set", "passage.end=0.06", "--set", "passage.start=-0.015",
                   "--set", "rail.half_width=0.02", "--set", "contact.dx=6e-4", "--set", "contact.dy=1.5e-3",
                   "--set", f"contact.normal={normal}", "--set", "contact.profile_grid_scale=2.0"]
            if bad:
                cmd += ["--set", "contact.regularisation=-1"]
            done = subprocess.run(cmd, capture_output=True, text=True)
            assert bad or done.returncode == 0, done.stderr
            rows.append({"wavelength": str(wavelength), "amplitude": str(amplitude), "normal": normal,
                         "file": str(f), "exit_code": str(done.returncode),
                         "message": done.stderr.splitlines()[0] if done.returncode else "", "contact_loss": "0"})
    out = evaluate(rows)
    assert [(r["wavelength"], r["amplitude"]) for r in out] == [(0.015, 1e-5), (0.03, 1e-5)]
    failed, both = out
    assert failed["outcome"].startswith("hertz failed") and "invalid config" in failed["outcome"]
    assert math.isnan(failed["harmonic_difference"])
    assert both["outcome"] == "both"
    # The two contacts differ at 30 mm (the contact filter along the rail,
    # the pressure on the crests) but wear about alike on average.
    assert 0.05 < both["harmonic_difference"] < 2.0 and both["mean_difference"] < 0.05
    assert 0.2 < both["amplitude_ratio"] < 5.0 and abs(both["phase_difference"]) <= 180.0
    assert "| 30 | 10 |" in markdown(out)
    chart(out, tmp_path / "map.png")
    assert (tmp_path / "map.png").stat().st_size > 1000


@pytest.mark.skipif(not BIN, reason="CORRUGATION_BIN not set (scripts/test.sh sets it)")
def test_validity_map_of_the_linear_contact(tmp_path):
    # The candidate is read from the manifest: "linear" against "profile"
    # at 30 mm and 10 um, where the two agree within the linear range (the
    # the book's map: 4.4 % on the 0.4 mm grid).
    rows = []
    for amplitude in (0.0, 1e-5):
        for normal in ("linear", "profile"):
            f = tmp_path / f"{amplitude}_{normal}.h5"
            cmd = [BIN, "run", str(REPO / "configs" / "growth_exact.toml"), "-o", str(f),
                   "--set", "growth.passes=1", "--set", "growth.adaptive=false",
                   "--set", "growth.contact_history=[0]", "--set", "roughness.kind=harmonics",
                   "--set", f"roughness.harmonics=[{{amplitude = {amplitude}, wavelength = 0.03}}]",
                   "--set", "rail.x_max=0.06", "--set", "passage.end=0.06", "--set", "passage.start=-0.04",
                   "--set", "rail.half_width=0.02", "--set", f"contact.normal={normal}",
                   "--set", "contact.profile_grid_scale=2.0"]
            done = subprocess.run(cmd, capture_output=True, text=True)
            assert done.returncode == 0, done.stderr
            rows.append({"wavelength": "0.03", "amplitude": str(amplitude), "normal": normal, "file": str(f),
                         "exit_code": "0", "message": "", "contact_loss": "0"})
    (row,) = evaluate(rows)
    assert row["outcome"] == "both"
    assert row["harmonic_difference"] < 0.1 and row["mean_difference"] < 0.05, row
    chart([row], tmp_path / "map.png", "linear")
    with pytest.raises(ValueError):
        evaluate([dict(r, normal="hertz") if r["normal"] == "profile" else r for r in rows])
