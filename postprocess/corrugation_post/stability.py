"""Stability map: the outcome of each run of ``scripts/stability_map.sh``.

Input: a manifest CSV with columns ``sweep, value, file, exit_code,
message`` (one row per run; the row with sweep ``baseline`` is the
reference). Output: ``stability.csv`` and ``stability.md`` with, per run,
whether it converged (exit code 0) or the program's error, the mean and
largest iterations per step (Newton iterations or Gauss-Seidel sweeps), the CPU time, and the relative L2
difference of the centre-line wear against the baseline (for runs with the
same rail grid and load).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .io import Run, RunFileError, read_csv, write_csv

COLUMNS = ("sweep", "value", "outcome", "newton_mean", "newton_max", "cpu_seconds", "wear_l2_vs_baseline",
           "message")


def _load(path):
    run = Run.open(path)
    with run.rail() as rail:
        w = rail["wear"].isel({"pass": -1}).sel(y=0.0, method="nearest").values
        x = rail["x"].values
    with run.contact(run.contact_passes()[0]) as ct:
        it = ct["newton_iterations"].values
        contact = ct["in_contact"].values > 0
    with run.pass_table() as ps:
        cpu = float(ps["cpu_seconds"].values.sum())
    return x, w, it[contact] if contact.any() else it, cpu


def evaluate(rows):
    base = next((r for r in rows if r["sweep"] == "baseline"), None)
    if base is None or int(base["exit_code"]) != 0:
        raise RunFileError("the baseline run is missing or failed: no reference for the wear differences")
    bx, bw, _, _ = _load(base["file"])
    out = []
    for r in rows:
        row = {"sweep": r["sweep"], "value": r["value"], "message": r.get("message", "")}
        if int(r["exit_code"]) != 0:
            row.update(outcome=f"error (exit {r['exit_code']})", newton_mean=math.nan, newton_max=math.nan,
                       cpu_seconds=math.nan, wear_l2_vs_baseline=math.nan)
        else:
            x, w, it, cpu = _load(r["file"])
            same = r["sweep"] in ("baseline", "eps", "step")
            l2 = float(np.linalg.norm(np.interp(bx, x, w) - bw) / np.linalg.norm(bw)) if same else math.nan
            row.update(outcome="converged", newton_mean=float(np.mean(it)), newton_max=float(np.max(it)),
                       cpu_seconds=cpu, wear_l2_vs_baseline=l2)
        out.append(row)
    return out


def markdown(rows) -> str:
    lines = ["| sweep | value | outcome | iterations per step (mean / max) | CPU s | wear vs baseline |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        it = "" if math.isnan(r["newton_mean"]) else f"{r['newton_mean']:.1f} / {r['newton_max']:.0f}"
        cpu = "" if math.isnan(r["cpu_seconds"]) else f"{r['cpu_seconds']:.1f}"
        l2 = "" if math.isnan(r["wear_l2_vs_baseline"]) else f"{r['wear_l2_vs_baseline']:.4f}"
        outcome = r["outcome"] + (f": {r['message']}" if r["message"] else "")
        lines.append(f"| {r['sweep']} | {r['value']} | {outcome} | {it} | {cpu} | {l2} |")
    return "\n".join(lines)


def run(manifest: Path, out_dir: Path):
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = evaluate(read_csv(manifest))
    table = write_csv(out_dir / "stability.csv", COLUMNS, rows)
    md = out_dir / "stability.md"
    md.write_text(markdown(rows) + "\n")
    return rows, [table, md]
