"""`corrugation-post mechanisms`: the summary's peaks and growing
harmonics from synthetic speeds.csv files, the figure, and a folder
without speeds.csv refused (exit 2)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from corrugation_post.io import RunFileError, write_csv
from corrugation_post.mechanisms import mechanism_figure
from corrugation_post.speeds import CSV_COLUMNS, CSV_NAME


def _write(folder, studies):
    folder.mkdir()
    rows = []
    for label, speed, rates in studies:
        for wl, g in rates.items():
            rows.append({"label": label, "speed_m_s": speed, "wavelength_m": wl, "frequency_hz": speed / wl,
                         "growth_rate_db_per_1e5": g, "predicted_db_per_1e5": float("nan")})
    write_csv(folder / CSV_NAME, CSV_COLUMNS, rows)


def test_summary_and_figure(tmp_path):
    # A frequency-fixing mechanism: its peak at 1000 Hz at both speeds
    # (20 and 30 mm); a wavelength-fixing one: at 50 mm at both.
    _write(tmp_path / "fixed_f", [("a_v72", 20.0, {0.02: 1.5, 0.03: -0.2, 0.05: 0.05}),
                                  ("a_v108", 30.0, {0.02: -0.3, 0.03: 1.2, 0.05: float("nan")})])
    _write(tmp_path / "fixed_wl", [("b_v72", 20.0, {0.02: -1.0, 0.05: 0.7}), ("b_v108", 30.0, {0.02: -1.0, 0.05: 0.9})])
    rows, paths = mechanism_figure([tmp_path / "fixed_f", tmp_path / "fixed_wl"], tmp_path / "out")
    by = {r["label"]: r for r in rows}
    assert by["a_v72"]["peak_frequency_hz"] == pytest.approx(1000.0)
    assert by["a_v108"]["peak_frequency_hz"] == pytest.approx(1000.0)
    assert by["b_v72"]["peak_wavelength_m"] == by["b_v108"]["peak_wavelength_m"] == 0.05
    assert by["a_v72"]["growing"] == "20.0 mm +1.50"  # 0.05 dB is below GROWING
    assert all(p.exists() for p in paths) and paths[0].name == "mechanisms.png"


def test_a_folder_without_speeds_is_refused(tmp_path):
    (tmp_path / "empty").mkdir()
    with pytest.raises(RunFileError, match="no speeds.csv"):
        mechanism_figure([tmp_path / "empty"], tmp_path / "out")
    done = subprocess.run([sys.executable, "-m", "corrugation_post", "mechanisms", str(tmp_path / "empty"), "--out",
                           str(tmp_path / "out")], capture_output=True, text=True)
    assert done.returncode == 2, done.stderr
    assert "no speeds.csv" in done.stderr
