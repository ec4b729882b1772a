"""Both rails of a wheelset: a run file with the group ``second_rail`` (the
layout of the root's rail, passes and contact groups) is listed, checked and
drawn rail by rail; a one-rail file is drawn as before."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import h5py
import pytest
import xarray as xr
from matplotlib.figure import Figure

from corrugation_post import io
from corrugation_post.cli import main
from corrugation_post.figures import make_figures
from corrugation_post.growth import compare_growth, format_table
from corrugation_post.schema import check_file
from synthetic_run import RAIL_NAMES, write_rail, write_run

BIN = os.environ.get("CORRUGATION_BIN")
REPO = Path(__file__).resolve().parents[2]
CONFIG = REPO / "configs" / "curve_two_rails.toml"
# The figures of one rail each: a second file per figure for the second rail.
PER_RAIL = ("wear_map", "wear_centreline", "loads", "traction_snapshots", "profile_snapshots")
# The figures that draw both rails.
BOTH = ("spectrum", "rms_corrugation", "spectrogram", "levels", "level_growth")


@pytest.fixture
def two_rails(tmp_path) -> Path:
    return write_run(tmp_path / "two.h5", n_pass=3, extras=True, growth=True, second_rail=True)


@pytest.fixture
def drawn(monkeypatch) -> dict[str, Figure]:
    """File name -> the Figure saved under it, while a test runs."""
    figures, save = {}, Figure.savefig

    def record(fig, fname, *args, **kwargs):
        figures[Path(fname).name] = fig
        return save(fig, fname, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", record)
    return figures


def _titles(fig: Figure) -> str:
    """The figure's title, then its axes' titles."""
    texts = [fig.get_suptitle()] + [ax.get_title() for ax in fig.axes]
    return "\n".join(t for t in texts if t)


def test_the_rails_of_a_file(two_rails, synthetic_run):
    assert io.rails(two_rails) == [io.RailGroups(RAIL_NAMES[0], ""), io.RailGroups(RAIL_NAMES[1], "second_rail/")]
    assert io.rails(synthetic_run) == [io.RailGroups("rail", "")]
    first, second = io.Run.open(two_rails).rails()
    assert (first.rail_name, second.rail_name, second.suffix) == (*RAIL_NAMES, "_second_rail")
    assert second.passes() == first.passes() and second.contact_passes() == [0, 1, 2]
    assert io.Run.open(synthetic_run).rail_name == ""
    with second.pass_table() as ps, xr.open_dataset(two_rails, engine="h5netcdf", group="second_rail/passes") as raw:
        assert float(ps["rms_corrugation"][-1]) == float(raw["rms_corrugation"][-1])
    with first.pass_table() as a, second.pass_table() as b:
        assert float(b["rms_corrugation"][-1]) > 1.5 * float(a["rms_corrugation"][-1])


def test_check_accepts_a_two_rail_file(two_rails, capsys):
    assert check_file(two_rails) == []
    assert main(["check", str(two_rails)]) == 0


def test_check_reports_a_second_rail_with_a_passage_fewer(two_rails, capsys):
    with h5py.File(two_rails, "a") as f:
        for group in ("rail", "passes", "contact"):
            del f[f"second_rail/{group}"]
    write_rail(two_rails, "second_rail/", 2, 1.7, 1.7, extras=True, growth=True)
    problems = check_file(two_rails)
    assert "second_rail/rail/pass: 2 passages, the first rail's rail/pass has 3" in problems
    assert "second_rail/passes/pass: 2 passages, the first rail's passes/pass has 3" in problems
    assert main(["check", str(two_rails)]) == 1
    assert "second_rail/passes/traffic" in capsys.readouterr().out


def test_check_reports_an_unnamed_rail_and_a_missing_group(two_rails):
    with h5py.File(two_rails, "a") as f:
        del f["second_rail"].attrs["rail_name"]
        del f["second_rail/passes"]
    problems = check_file(two_rails)
    assert "second_rail: missing attribute 'rail_name' (the file has a second rail)" in problems
    assert any("cannot open group 'second_rail/passes'" in p for p in problems)


def test_check_reports_other_traffic_on_the_second_rail_and_one_name_for_both(two_rails):
    with h5py.File(two_rails, "a") as f:
        f["second_rail/passes/traffic"][-1] += 1
        f["second_rail"].attrs["rail_name"] = RAIL_NAMES[0]
    assert f"second_rail: rail_name {RAIL_NAMES[0]!r} is the first rail's too" in check_file(two_rails)
    assert any(p.startswith("second_rail/passes/traffic: differs") for p in check_file(two_rails))


def test_figures_of_both_rails(two_rails, tmp_path, drawn, capsys):
    out = tmp_path / "figs"
    assert main(["figures", str(two_rails), "--out", str(out)]) == 0
    written = {Path(line).name for line in capsys.readouterr().out.split()}
    assert written == {f"{n}{s}.png" for n in PER_RAIL for s in ("", "_second_rail")} | {f"{n}.png" for n in BOTH}
    rms = drawn["rms_corrugation.png"].axes[0]
    assert [line.get_label() for line in rms.get_lines()] == list(RAIL_NAMES)
    assert [t.get_text() for t in rms.get_legend().get_texts()] == list(RAIL_NAMES)
    for name in ("spectrum.png", "levels.png"):
        labels = [line.get_label() for line in drawn[name].axes[0].get_lines()]
        assert all(any(label.startswith(r) for label in labels) for r in RAIL_NAMES), (name, labels)
    maps = [ax.get_title() for ax in drawn["spectrogram.png"].axes if ax.get_title().endswith("fastsim")]
    assert [t.split(":")[0] for t in maps] == list(RAIL_NAMES)
    assert [ax.get_title() for ax in drawn["level_growth.png"].axes] == list(RAIL_NAMES)
    for name in PER_RAIL:
        assert _titles(drawn[f"{name}.png"]).startswith(f"{RAIL_NAMES[0]}: "), name
        assert _titles(drawn[f"{name}_second_rail.png"]).startswith(f"{RAIL_NAMES[1]}: "), name


def test_one_rail_figures_name_no_rail(tmp_path, drawn):
    run = write_run(tmp_path / "one.h5", n_pass=3, extras=True, growth=True)
    paths, problems, notes = make_figures(run, tmp_path / "figs")
    assert not problems and not notes
    assert {p.name for p in paths} == {f"{n}.png" for n in PER_RAIL + BOTH}
    rms = drawn["rms_corrugation.png"].axes[0]
    assert len(rms.get_lines()) == 1 and rms.get_legend() is None
    assert rms.get_title().startswith("The rms corrugation grows")
    assert all("rail:" not in _titles(fig) for fig in drawn.values())


def test_a_second_rail_without_contact_history(two_rails, tmp_path, capsys):
    with h5py.File(two_rails, "a") as f:
        del f["second_rail/contact"]
    out = tmp_path / "o"
    assert main(["figures", str(two_rails), "--out", str(out)]) == 0
    err = capsys.readouterr().err
    assert f"({RAIL_NAMES[1]}): no contact history" in err and "loads_second_rail.png" in err
    assert (out / "loads.png").is_file() and not (out / "loads_second_rail.png").exists()
    assert check_file(two_rails) == []


def test_growth_table_names_each_rail(two_rails, tmp_path):
    rows, _ = compare_growth([two_rails], tmp_path)
    assert [r["label"] for r in rows] == [f"two ({name})" for name in RAIL_NAMES]
    table = format_table(rows)
    assert all(f"two ({name})" in table for name in RAIL_NAMES)


@pytest.mark.skipif(not BIN, reason="CORRUGATION_BIN not set (scripts/test.sh sets it)")
@pytest.mark.skipif(not CONFIG.is_file(), reason=f"{CONFIG.name} not in this checkout")
def test_the_binary_writes_both_rails(tmp_path, capsys):
    out = tmp_path / "two_rails.h5"
    # One passage on a coarse grid (the file's layout, not its numbers, is
    # tested here): a third of the shipped grid's cost.
    coarse = ["growth.passes=1", "contact.dx=1.2e-3", "contact.dy=2e-3", "rail.dx=6e-4", "rail.dy=1e-3"]
    done = subprocess.run([BIN, "run", str(CONFIG), "-o", str(out), *[a for s in coarse for a in ("--set", s)]],
                          capture_output=True, text=True, cwd=REPO)
    assert done.returncode == 0, done.stderr
    names = [r.name for r in io.rails(out)]
    assert len(names) == 2 and names[0] != names[1], names
    assert check_file(out) == []
    with xr.open_dataset(out, engine="h5netcdf", group="second_rail/passes") as ps:
        assert ps["rms_corrugation"].attrs["units"] == "m"
    assert main(["figures", str(out), "--out", str(tmp_path / "figs")]) == 0
    written = {Path(line).name for line in capsys.readouterr().out.split()}
    assert {"wear_map.png", "wear_map_second_rail.png"} <= written


def test_speeds_and_mechanisms_draw_both_rails(two_rails, tmp_path):
    # `speeds` gives every rail of a two-rail study its own curve, rows and
    # summary row, named; a one-rail study keeps an empty rail column.
    from corrugation_post.mechanisms import mechanism_figure
    from corrugation_post.speeds import speed_study

    one_rail = write_run(tmp_path / "one.h5", n_pass=3, extras=True, growth=True)
    for f in (two_rails, one_rail):  # the speed, as a growth study's config gives it
        with h5py.File(f, "r+") as h:
            h.attrs["config"] = io.as_str(h.attrs["config"]) + "\n[rolling]\nspeed = 30.0\n"
    folder = tmp_path / "two_rails"
    summary, _ = speed_study([two_rails], folder)
    assert [r["rail"] for r in summary] == list(RAIL_NAMES)
    assert all(name in r["label"] for r, name in zip(summary, RAIL_NAMES))
    rows = io.read_csv(folder / "speeds.csv")
    assert {r["rail"] for r in rows} == set(RAIL_NAMES)
    one, _ = speed_study([one_rail], tmp_path / "one")
    assert [r["rail"] for r in one] == [""]
    mech, _ = mechanism_figure([folder], tmp_path / "mech")
    assert sorted(r["label"] for r in mech) == sorted(r["label"] for r in summary)
