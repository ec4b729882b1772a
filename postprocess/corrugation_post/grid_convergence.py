"""Grid convergence of the exact-transient model on both discretisations.

Input: a manifest CSV with columns ``scene, grid, size, file``: ``grid`` is
``fixed`` (``size`` = the element length contact.dx, m) or ``adapted``
(``size`` = elements per strip and strips, n x n). For every run, the
quantities a corrugation study needs:

* ``mean_wear``: the mean centre-line wear depth over whole load periods of
  the recorded stretch (m);
* ``harmonic_rel``: the amplitude of its first harmonic (the load
  wavelength) relative to the mean, in per cent;
* ``harmonic_phase``: its phase (degrees);
* ``mean_creepage``: the mean |creepage_x| with the patch on the stretch.

For each scene and discretisation the three finest runs give the observed
order of every quantity and its Richardson limit (refinement measure: 1/dx
for the fixed grid, n for the adapted mesh). Every run's error is taken
against the fixed grid's limit: relative for the mean wear and creepage,
in points for the harmonic, in degrees for the phase. The two limits'
difference is the check that both discretisations converge to the same
answer. Writes ``grid_convergence.csv`` (runs) and ``grid_limits.csv``.
"""

from __future__ import annotations

import math
from collections import defaultdict
from pathlib import Path

import numpy as np

from .accuracy_map import extrapolate
from .io import RunFileError, read_csv, write_csv
from .speed_accuracy import _curves, _harmonic, _wavelength

QUANTITIES = ("mean_wear", "harmonic_rel", "harmonic_phase", "mean_creepage")
RUN_COLUMNS = ("scene", "grid", "size", "cpu_seconds", *QUANTITIES, "err_mean_wear", "err_harmonic_points",
               "err_phase_deg", "err_creepage")
LIMIT_COLUMNS = ("scene", "grid", "sizes", *QUANTITIES, *(f"order_{q}" for q in QUANTITIES))


def metrics(path) -> dict:
    """The study's quantities of one run file."""
    x, w, creep, cpu = _curves(path)
    wavelength = _wavelength(path)
    periods = math.floor((x[-1] - x[0]) / wavelength + 1e-9)
    keep = x <= x[0] + periods * wavelength - 0.5 * (x[1] - x[0])
    mean = float(np.mean(w[keep]))
    h = _harmonic(x, w, wavelength)
    return {
        "cpu_seconds": cpu,
        "mean_wear": mean,
        "harmonic_rel": 100.0 * abs(h) / mean,
        "harmonic_phase": math.degrees(np.angle(h)),
        "mean_creepage": float(np.mean(np.abs(creep))),
    }


def _refinement(grid: str, size: float) -> float:
    return 1.0 / size if grid == "fixed" else size


def limits(runs: list[tuple[float, dict]]) -> dict:
    """Richardson limits and observed orders from the three finest runs
    [(refinement, metrics), ...]; NaN where the sequence does not converge."""
    (n1, m1), (n2, m2), (n3, m3) = sorted(runs, key=lambda r: r[0])[-3:]
    out = {}
    for q in QUANTITIES:
        v = [np.array([m[q]]) for m in (m1, m2, m3)]
        if q == "harmonic_phase":
            # Unwrap onto the finest run's branch.
            v = [v[2] + ((vi - v[2] + 180.0) % 360.0 - 180.0) for vi in v]
        try:
            limit, order = extrapolate((n1, n2, n3), *v)
            out[q], out[f"order_{q}"] = float(limit[0]), order
        except RunFileError:
            out[q], out[f"order_{q}"] = float(v[2][0]), math.nan
    return out


def evaluate(manifest_rows):
    """(run rows, limit rows): errors of every run against the fixed grid's
    limit of its scene."""
    groups = defaultdict(list)
    for r in manifest_rows:
        size = float(r["size"])
        groups[(r["scene"], r["grid"])].append((size, metrics(r["file"])))
    lim = {}
    limit_rows = []
    for (scene, grid), runs in sorted(groups.items()):
        if len(runs) < 3:
            continue
        refined = [(_refinement(grid, s), m) for s, m in runs]
        lim[(scene, grid)] = limits(refined)
        sizes = " / ".join(f"{s:g}" for s, _ in sorted(runs, key=lambda r: _refinement(grid, r[0])))
        limit_rows.append({"scene": scene, "grid": grid, "sizes": sizes, **lim[(scene, grid)]})
    run_rows = []
    for (scene, grid), runs in sorted(groups.items()):
        ref = lim.get((scene, "fixed"))
        for size, m in sorted(runs, key=lambda r: -_refinement(grid, r[0])):
            row = {"scene": scene, "grid": grid, "size": size, **m}
            if ref is None:
                row.update({k: math.nan for k in RUN_COLUMNS[-4:]})
            else:
                row["err_mean_wear"] = m["mean_wear"] / ref["mean_wear"] - 1.0
                row["err_harmonic_points"] = m["harmonic_rel"] - ref["harmonic_rel"]
                row["err_phase_deg"] = (m["harmonic_phase"] - ref["harmonic_phase"] + 180.0) % 360.0 - 180.0
                row["err_creepage"] = m["mean_creepage"] / ref["mean_creepage"] - 1.0
            run_rows.append(row)
    return run_rows, limit_rows


def run(manifest: Path, out_dir: Path):
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    runs, lims = evaluate(read_csv(manifest))
    return (runs, lims), [write_csv(out_dir / "grid_convergence.csv", RUN_COLUMNS, runs),
                          write_csv(out_dir / "grid_limits.csv", LIMIT_COLUMNS, lims)]


def format_table(result) -> str:
    runs, lims = result
    lines = [f"{'scene':<26} {'grid':<8} {'size':>8} {'cpu s':>8} {'mean wear':>11} {'h1 %':>7} {'phase':>8} "
             f"{'creepage':>10} {'d wear':>8} {'d h1':>7} {'d deg':>7} {'d creep':>8}"]
    for r in runs:
        lines.append(f"{r['scene']:<26} {r['grid']:<8} {r['size']:>8g} {r['cpu_seconds']:>8.2f} "
                     f"{r['mean_wear']:>11.5e} {r['harmonic_rel']:>7.3f} {r['harmonic_phase']:>8.3f} "
                     f"{r['mean_creepage']:>10.5e} {r['err_mean_wear']:>+8.4f} {r['err_harmonic_points']:>+7.3f} "
                     f"{r['err_phase_deg']:>+7.3f} {r['err_creepage']:>+8.4f}")
    lines.append("")
    lines.append(f"{'scene':<26} {'grid':<8} {'limit wear':>11} {'h1 %':>7} {'phase':>8} {'creepage':>10}  orders")
    for r in lims:
        orders = " ".join(f"{r[f'order_{q}']:.2f}" for q in QUANTITIES)
        lines.append(f"{r['scene']:<26} {r['grid']:<8} {r['mean_wear']:>11.5e} {r['harmonic_rel']:>7.3f} "
                     f"{r['harmonic_phase']:>8.3f} {r['mean_creepage']:>10.5e}  {orders}")
    return "\n".join(lines)
