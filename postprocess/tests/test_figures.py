"""The figures command writes non-empty PNGs."""

from __future__ import annotations

from pathlib import Path

import pytest

from corrugation_post import figures
from corrugation_post.cli import main
from synthetic_run import write_run

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
REQUIRED = ("wear_map.png", "wear_centreline.png", "loads.png", "traction_snapshots.png")


def _assert_png(path: Path):
    assert path.is_file(), path
    assert path.stat().st_size > 1000, path
    assert path.read_bytes()[:8] == PNG_MAGIC, path


def test_figures_command_writes_pngs(run_file, tmp_path, capsys):
    out = tmp_path / "figs"
    assert main(["figures", str(run_file), "--out", str(out)]) == 0
    printed = [Path(line) for line in capsys.readouterr().out.split()]
    for name in REQUIRED:
        assert out / name in printed
        _assert_png(out / name)


@pytest.mark.parametrize("make", [figures.wear_map, figures.wear_centreline,
                                  figures.loads, figures.traction_snapshots])
def test_each_figure_function(run_file, tmp_path, make):
    from corrugation_post.io import Run

    run = Run.open(run_file)
    _assert_png(make(run, run.passes()[0], tmp_path))


def test_explicit_pass(run_file, tmp_path):
    from corrugation_post.io import stored_passes

    # --pass counts passages from 1, as the terminal does.
    first = stored_passes(run_file)[0] + 1
    assert main(["figures", str(run_file), "--out", str(tmp_path), "--pass", str(first)]) == 0
    for name in REQUIRED:
        _assert_png(tmp_path / name)


def test_unknown_pass_is_an_error(run_file, tmp_path, capsys):
    assert main(["figures", str(run_file), "--out", str(tmp_path), "--pass", "987654"]) == 2
    err = capsys.readouterr().err
    assert "987654" in err and str(run_file) in err


def test_optional_and_unknown_variables(tmp_path, capsys):
    """Extra variables do not break anything; optional ones get their figures."""
    run = write_run(tmp_path / "extras.h5", extras=True)
    out = tmp_path / "figs"
    assert main(["figures", str(run), "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    for name in REQUIRED + ("spectrum.png", "rms_corrugation.png", "spectrogram.png", "profile_snapshots.png"):
        assert name in printed
        _assert_png(out / name)


def test_snapshot_steps_avoid_loss_of_contact():
    import numpy as np

    xc = np.linspace(0.0, 100.0, 101)
    contact = xc > 20
    steps = figures.snapshot_steps(xc, contact, 4)
    assert len(steps) == 4 and contact[steps].all()
    assert np.all(np.diff(xc[steps]) > 15)


def test_missing_contact_group_skips_contact_figures(tmp_path, capsys):
    # A run that keeps no contact history (growth.contact_history = []):
    # figures draws the rest and says what it left out, exit 0.
    import h5py

    run = write_run(tmp_path / "nocontact.h5", n_pass=1)
    with h5py.File(run, "a") as f:
        del f["contact"]
    assert main(["figures", str(run), "--out", str(tmp_path / "o")]) == 0
    captured = capsys.readouterr()
    assert "wear_map.png" in captured.out and "loads.png" not in captured.out
    assert "note:" in captured.err and "no contact history" in captured.err and "warning" not in captured.err
    assert main(["check", str(run)]) == 0


def test_contact_figures_of_the_nearest_kept_passage(tmp_path, capsys):
    # The last passage has no contact history (contact_history = [0, 149] on
    # a shorter study): the contact figures show the latest one kept, said in
    # a note, exit 0; titles count passages from 1.
    import h5py

    run = write_run(tmp_path / "partial.h5", n_pass=3)
    with h5py.File(run, "a") as f:
        del f["contact/pass_00002"]
        del f["contact/pass_00001"]
    out = tmp_path / "o"
    assert main(["figures", str(run), "--out", str(out)]) == 0
    captured = capsys.readouterr()
    assert "passage 3 has no contact history" in captured.err and "show passage 1" in captured.err
    _assert_png(out / "loads.png")
    assert main(["check", str(run)]) == 0
    assert main(["figures", str(run), "--out", str(out), "--pass", "0"]) == 2
    assert "stored passages (counted from 1): 1, 2, 3" in capsys.readouterr().err


def test_missing_variable_is_reported_and_other_figures_still_made(tmp_path, capsys):
    import h5py

    run = write_run(tmp_path / "broken.h5", n_pass=1)
    with h5py.File(run, "a") as f:
        del f["contact/pass_00000/semi_axis_b"]
    out = tmp_path / "o"
    assert main(["figures", str(run), "--out", str(out)]) == 1
    captured = capsys.readouterr()
    assert "semi_axis_b" in captured.err and str(run) in captured.err
    for name in ("wear_map.png", "wear_centreline.png", "traction_snapshots.png"):
        _assert_png(out / name)


def test_a_run_without_stored_fields_draws_the_rest_and_passes_the_check(tmp_path, capsys):
    # output.store_fields = false: the contact history keeps the per-step
    # values only. figures leaves out the traction snapshots with a note
    # (exit 0) and check finds nothing wrong.
    import h5py

    from corrugation_post.schema import FIELDS

    run = write_run(tmp_path / "nofields.h5", n_pass=1)
    with h5py.File(run, "a") as f:
        for v in FIELDS:
            del f[f"contact/pass_00000/{v}"]
    out = tmp_path / "o"
    assert main(["figures", str(run), "--out", str(out)]) == 0
    captured = capsys.readouterr()
    assert "store_fields = false" in captured.err and "warning" not in captured.err
    _assert_png(out / "loads.png")
    assert not (out / "traction_snapshots.png").exists()
    assert main(["check", str(run)]) == 0


def test_the_wear_map_shows_the_variation_along_the_rail(tmp_path, monkeypatch):
    """A wear that varies by 1 % along the rail: the lower panel draws the
    depth minus its mean along x on a symmetric scale and says the share."""
    import numpy as np
    from matplotlib.figure import Figure

    from corrugation_post.io import Run

    path = write_run(tmp_path / "w.h5", n_pass=1)
    import h5py

    with h5py.File(path, "a") as f:
        w = f["rail/wear"]
        x = f["rail/x"][:]
        base = np.ones(w.shape[1:])
        ripple = 1.0 + 0.01 * np.cos(2 * np.pi * x / (x[-1] - x[0] + (x[1] - x[0])) * 3)
        w[0] = 1e-10 * base * ripple[np.newaxis, :]
    saved = {}
    save = Figure.savefig

    def record(fig, fname, *args, **kwargs):
        saved["fig"] = fig
        return save(fig, fname, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", record)
    run = Run.open(path)
    figures.wear_map(run, run.passes()[0], tmp_path)
    lower = [ax for ax in saved["fig"].axes if ax.get_title().startswith("its variation along the rail")]
    assert len(lower) == 1
    assert "up to 1 %" in lower[0].get_title(), lower[0].get_title()
    # Symmetric about zero, at the variation's peak (1e-12 m = 1e-3 nm).
    mesh = lower[0].collections[0]
    assert mesh.norm.vmin == -mesh.norm.vmax
    assert abs(mesh.norm.vmax - 1e-3) < 1e-6, mesh.norm.vmax
