"""Helpful errors: non-zero exit and a message naming the file."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import h5py
import pytest

from corrugation_post.cli import main


def _bad_files(tmp_path):
    no_rail = tmp_path / "no_rail.h5"
    with h5py.File(no_rail, "w") as f:
        f.create_group("passes")
        f.attrs["contact_model"] = "fastsim"
    text = tmp_path / "notes.h5"
    text.write_text("not hdf5")
    return {"missing": (tmp_path / "missing.h5", "no such file"),
            "no_rail": (no_rail, "no 'rail' group"),
            "not_hdf5": (text, "not an HDF5 file")}


@pytest.mark.parametrize("case", ["missing", "no_rail", "not_hdf5"])
@pytest.mark.parametrize("command", ["figures", "check"])
def test_bad_input_in_process(tmp_path, capsys, case, command):
    path, words = _bad_files(tmp_path)[case]
    argv = [command, str(path)] + (["--out", str(tmp_path / "o")] if command == "figures" else [])
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert str(path) in err and words in err
    assert not (tmp_path / "o").exists()


# The installed console command (scripts/setup.sh installs the package into
# the venv that runs these tests), and ``python -m corrugation_post``.
COMMANDS = {
    "console": [str(Path(sys.executable).parent / "corrugation-post")],
    "python_m": [sys.executable, "-m", "corrugation_post"],
}


@pytest.mark.parametrize("entry", ["console", "python_m"])
@pytest.mark.parametrize("case", ["missing", "no_rail"])
def test_bad_input_via_the_entry_points(tmp_path, case, entry):
    """The real entry points, run as subprocesses."""
    path, words = _bad_files(tmp_path)[case]
    env = dict(os.environ, MPLBACKEND="Agg")
    proc = subprocess.run(
        COMMANDS[entry] + ["figures", str(path), "--out", str(tmp_path / "o")],
        capture_output=True, text=True, env=env, cwd=tmp_path, timeout=120,
    )
    assert proc.returncode != 0
    assert str(path) in proc.stderr and words in proc.stderr
    assert "Traceback" not in proc.stderr


def test_console_command_figures_prints_paths(run_file, tmp_path):
    proc = subprocess.run(
        COMMANDS["console"] + ["figures", str(run_file), "--out", str(tmp_path / "o")],
        capture_output=True, text=True, cwd=tmp_path, timeout=300,
    )
    assert proc.returncode == 0, proc.stderr
    printed = proc.stdout.split()
    assert str(tmp_path / "o" / "wear_map.png") in printed


def test_usage_error_exits_non_zero(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["figures"])
    assert exc.value.code != 0
