"""Comparison of several runs (e.g. one per contact model) on the same passage.

Overlays centre-line wear and creepage, and tabulates relative differences of
the maximum centre-line wear depth and of the mean |creepage_x| against the
first run.  Relative difference = (value - reference) / |reference|.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from .figures import DPI, contact_mask
from .io import Run, RunFileError
from .io import write_csv as io_write_csv
from .units import values_in

CSV_NAME = "compare.csv"
CSV_COLUMNS = (
    "label", "file", "pass",
    "max_centreline_wear_m", "max_centreline_wear_rel_diff",
    "mean_abs_creepage_x", "mean_abs_creepage_x_rel_diff",
    "centreline_wear_rel_l2_diff",
)


@dataclass
class RunCurves:
    """What the comparison needs from one run."""

    label: str
    path: Path
    pass_index: int
    x_mm: np.ndarray
    centreline_um: np.ndarray
    xc_mm: np.ndarray | None
    creepage_x: np.ndarray | None
    max_centreline_wear_m: float
    mean_abs_creepage_x: float


def _common_pass(runs: list[Run], requested: int | None) -> int:
    """The stored index of passage ``requested`` (counted from 1, checked in
    every run), else of the last passage stored in all runs."""
    if requested is not None:
        return [run.resolve_pass(requested) for run in runs][0]
    common = set.intersection(*(set(run.passes()) for run in runs))
    if not common:
        raise RunFileError("the runs have no stored passage index in common; use --pass")
    return max(common)


def _labels(runs: list[Run]) -> list[str]:
    """Contact-model labels, with the file name added where two runs share a model."""
    models = [run.contact_model for run in runs]
    return [m if models.count(m) == 1 else f"{m} ({run.path.stem})" for m, run in zip(models, runs)]


def load_curves(run: Run, label: str, pass_index: int) -> RunCurves:
    """Centre-line wear and creepage of one run (creepage is None without contact history).

    Mean |creepage_x| is taken over in-contact steps only.
    """
    with run.rail() as rail:
        row = rail["wear"].sel({"pass": pass_index}).sel(y=0.0, method="nearest").load()
        x_mm = values_in(rail["x"], "mm")
    wear_m = values_in(row, "m")
    xc = cx = None
    mean_cx = math.nan
    if pass_index in run.contact_passes():
        with run.contact(pass_index) as ct:
            xc = values_in(ct["x_c"], "mm")
            cx = values_in(ct["creepage_x"], "1")
            contact = contact_mask(ct.load())
        if contact.any():
            mean_cx = float(np.mean(np.abs(cx[contact])))
    return RunCurves(label, run.path, pass_index, x_mm, wear_m * 1e6, xc, cx,
                     float(np.nanmax(wear_m)), mean_cx)


def _rel(value: float, ref: float) -> float:
    return (value - ref) / abs(ref) if ref and math.isfinite(ref) else math.nan


def _profile_l2_diff(c: RunCurves, ref: RunCurves) -> float:
    """||w - w_ref|| / ||w_ref|| of the centre-line wear, on the reference's x."""
    w = np.interp(ref.x_mm, c.x_mm, c.centreline_um)
    norm = float(np.sqrt(np.sum(ref.centreline_um ** 2)))
    return float(np.sqrt(np.sum((w - ref.centreline_um) ** 2))) / norm if norm > 0 else math.nan


def table_rows(curves: list[RunCurves]) -> list[dict]:
    """One row per run, relative differences against the first run."""
    ref = curves[0]
    return [
        {
            "label": c.label, "file": str(c.path), "pass": c.pass_index + 1,
            "max_centreline_wear_m": c.max_centreline_wear_m,
            "max_centreline_wear_rel_diff": _rel(c.max_centreline_wear_m, ref.max_centreline_wear_m),
            "mean_abs_creepage_x": c.mean_abs_creepage_x,
            "mean_abs_creepage_x_rel_diff": _rel(c.mean_abs_creepage_x, ref.mean_abs_creepage_x),
            "centreline_wear_rel_l2_diff": _profile_l2_diff(c, ref),
        }
        for c in curves
    ]


def format_table(rows: list[dict]) -> str:
    """Plain-text table for the terminal."""
    head = (f"{'label':<28} {'max wear (um)':>14} {'rel diff':>9} {'mean |cx|':>11} {'rel diff':>9}"
            f" {'profile L2 diff':>16}")
    lines = [head, "-" * len(head)]
    for r in rows:
        lines.append(
            f"{r['label'][:28]:<28} {r['max_centreline_wear_m'] * 1e6:>14.5g} "
            f"{r['max_centreline_wear_rel_diff']:>+9.2%} {r['mean_abs_creepage_x']:>11.4g} "
            f"{r['mean_abs_creepage_x_rel_diff']:>+9.2%} {r['centreline_wear_rel_l2_diff']:>16.2%}"
        )
    return "\n".join(lines)


def _overlay(curves: list[RunCurves], out_dir: Path) -> list[Path]:
    pass_index = curves[0].pass_index
    fig = Figure(figsize=(9, 4), layout="constrained")
    ax = fig.add_subplot()
    for c in curves:
        ax.plot(c.x_mm, c.centreline_um, label=c.label)
    ax.set(xlabel="x along rail (mm)", ylabel="wear depth at y ≈ 0 (µm)",
           title=f"Centre-line wear depth of passage {pass_index + 1}")
    ax.grid(alpha=0.3)
    ax.legend()
    wear_png = out_dir / "compare_wear_centreline.png"
    fig.savefig(wear_png, dpi=DPI)

    fig = Figure(figsize=(9, 4), layout="constrained")
    ax = fig.add_subplot()
    for c in curves:
        if c.creepage_x is not None:
            ax.plot(c.xc_mm, c.creepage_x, label=c.label)
    ax.set(xlabel="patch centre x_c (mm)", ylabel="creepage_x (signed)",
           title=f"Longitudinal creepage, passage {pass_index + 1}")
    ax.grid(alpha=0.3)
    ax.legend()
    creep_png = out_dir / "compare_creepage.png"
    fig.savefig(creep_png, dpi=DPI)
    return [wear_png, creep_png]


def _side_by_side_maps(runs: list[Run], labels: list[str], pass_index: int, out_dir: Path) -> Path:
    """Wear maps of every run, one panel each, on a common colour scale."""
    maps = []
    for run in runs:
        with run.rail() as rail:
            wear = rail["wear"].sel({"pass": pass_index}).transpose("y", "x").load()
            maps.append((values_in(rail["x"], "mm"), values_in(rail["y"], "mm"), values_in(wear, "um")))
    vmax = max(float(np.nanmax(m[2])) for m in maps) or 1.0
    fig = Figure(figsize=(9, 2.6 * len(maps) + 0.6), layout="constrained")
    axes = fig.subplots(len(maps), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (x, y, w), label in zip(axes, maps, labels):
        mesh = ax.pcolormesh(x, y, w, shading="auto", cmap="viridis", vmin=0.0, vmax=vmax)
        ax.set(ylabel="y (mm)", title=label)
    axes[-1].set_xlabel("x along rail (mm)")
    fig.colorbar(mesh, ax=list(axes), label="wear depth (µm)")
    fig.suptitle(f"Wear depth of passage {pass_index + 1} alone")
    path = out_dir / "compare_wear_maps.png"
    fig.savefig(path, dpi=DPI)
    return path


def write_csv(rows: list[dict], path: Path) -> Path:
    return io_write_csv(path, CSV_COLUMNS, rows)


def compare_runs(paths, out_dir, pass_index: int | None = None):
    """Compare runs; returns ``(rows, written_paths, problems)``.

    The first run is the reference.  Raises RunFileError for an unusable file.
    """
    runs = [Run.open(p) for p in paths]
    pass_index = _common_pass(runs, pass_index)
    curves = [load_curves(run, label, pass_index) for run, label in zip(runs, _labels(runs))]
    problems = [f"{c.path}: no contact history for passage {pass_index}; creepage left out"
                for c in curves if c.creepage_x is None]
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = table_rows(curves)
    maps = _side_by_side_maps(runs, [c.label for c in curves], pass_index, out_dir)
    written = _overlay(curves, out_dir) + [maps, write_csv(rows, out_dir / CSV_NAME)]
    return rows, written, problems
