"""The compare command writes its CSV with one row per run."""

from __future__ import annotations

import csv

import pytest

from corrugation_post.cli import main
from corrugation_post.compare import CSV_COLUMNS
from synthetic_run import write_run


def _read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_compare_run_with_itself(run_file, tmp_path, capsys):
    out = tmp_path / "cmp"
    assert main(["compare", str(run_file), str(run_file), "--out", str(out)]) == 0
    rows = _read(out / "compare.csv")
    assert len(rows) == 2
    assert tuple(rows[0]) == CSV_COLUMNS
    for row in rows:
        assert float(row["max_centreline_wear_rel_diff"]) == 0.0
        assert float(row["mean_abs_creepage_x_rel_diff"]) == 0.0
        assert float(row["centreline_wear_rel_l2_diff"]) == 0.0
    for name in ("compare_wear_centreline.png", "compare_creepage.png", "compare_wear_maps.png"):
        assert (out / name).stat().st_size > 1000
    assert "compare.csv" in capsys.readouterr().out


def test_compare_relative_differences(tmp_path, capsys):
    ref = write_run(tmp_path / "a.h5", contact_model="exact-transient")
    other = write_run(tmp_path / "b.h5", contact_model="fastsim", wear_scale=1.25, creep_scale=0.8)
    third = write_run(tmp_path / "c.h5", contact_model="simplified-transient", wear_scale=0.5)
    out = tmp_path / "cmp"
    assert main(["compare", str(ref), str(other), str(third), "--out", str(out)]) == 0
    rows = _read(out / "compare.csv")
    assert [r["label"] for r in rows] == ["exact-transient", "fastsim", "simplified-transient"]
    assert [r["file"] for r in rows] == [str(ref), str(other), str(third)]
    rel_wear = [float(r["max_centreline_wear_rel_diff"]) for r in rows]
    rel_creep = [float(r["mean_abs_creepage_x_rel_diff"]) for r in rows]
    assert rel_wear == pytest.approx([0.0, 0.25, -0.5])
    assert rel_creep == pytest.approx([0.0, -0.2, 0.0])
    # A uniformly scaled profile differs by |scale - 1| in the L2 sense.
    l2 = [float(r["centreline_wear_rel_l2_diff"]) for r in rows]
    assert l2 == pytest.approx([0.0, 0.25, 0.5])
    table = capsys.readouterr().out
    assert "fastsim" in table and "+25.00%" in table


def test_compare_same_model_labels_are_distinguished(tmp_path):
    a = write_run(tmp_path / "a.h5")
    b = write_run(tmp_path / "b.h5")
    assert main(["compare", str(a), str(b), "--out", str(tmp_path / "o")]) == 0
    labels = [r["label"] for r in _read(tmp_path / "o" / "compare.csv")]
    assert labels == ["fastsim (a)", "fastsim (b)"]


def test_compare_missing_file_is_an_error(run_file, tmp_path, capsys):
    missing = tmp_path / "nope.h5"
    assert main(["compare", str(run_file), str(missing), "--out", str(tmp_path)]) == 2
    assert str(missing) in capsys.readouterr().err
    assert not (tmp_path / "compare.csv").exists()
