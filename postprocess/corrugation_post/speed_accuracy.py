"""Speed against accuracy of the contact models.

Input: a manifest CSV with columns ``scene, model, mesh, file, reference``
(one row per run; ``reference`` is 1 for the run every other run of the same
scene is compared with, the finest exact-transient run). For every run the
errors against its scene's reference are:

* ``wear_l2``: relative L2 difference of the centre-line wear profile
  ``||w - w_ref|| / ||w_ref||`` on the recorded stretch (dominated by the
  mean wear depth);
* ``wear_fluct_l2``: the same for the profile minus its mean, the part that
  makes corrugation (``||w' - w'_ref|| / ||w'_ref||``);
* ``harmonic_amp``: relative error of the amplitude of the centre-line wear
  at the imposed load wavelength (the first harmonic, which drives growth);
* ``harmonic_phase``: its phase error (rad, wrapped to (-pi, pi]);
* ``creepage_l2``: relative L2 difference of the creepage history
  ``creepage_x(x_c)`` (interpolated onto the reference's steps) over the
  steps with the patch centre on the recorded stretch (after the run-in, whose first, Cattaneo step of the transient
  models has a creepage ~50 times the steady one);

and the cost is the CPU time of the passage (``passes/cpu_seconds``; the
median over repeated runs when the manifest lists the same run several
times). Writes ``speed_accuracy.csv`` and ``speed_accuracy.png`` (wear
error against CPU time, one curve per model, the Pareto front over all
models of a scene circled).
"""

from __future__ import annotations

import math
from collections import defaultdict
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from .figures import DPI
from .io import Run, RunFileError, parse_config, read_csv, root_attrs, write_csv

CSV_COLUMNS = ("scene", "model", "mesh", "repeats", "cpu_seconds", "wear_l2", "wear_fluct_l2", "harmonic_amp",
               "harmonic_phase", "creepage_l2", "pareto")
MARKERS = {"exact-transient": "o", "exact-fixed": "D", "simplified-transient": "s", "fastsim": "^"}


def _wavelength(path) -> float:
    """The imposed load wavelength (m) of a run: its first load harmonic."""
    config = parse_config(root_attrs(path)["config"], path)
    harmonics = config.get("load", {}).get("harmonics", [])
    if not harmonics:
        raise RunFileError(f"{path}: no load harmonic: the first-harmonic error needs one")
    return float(harmonics[0]["wavelength"])


def _curves(path):
    """Centre-line wear (x, w) over the recorded stretch and creepage_x(step)."""
    run = Run.open(path)
    with run.rail() as rail:
        last = int(rail["pass"].values[-1])
        w = rail["wear"].sel({"pass": last}).sel(y=0.0, method="nearest").values
        x = rail["x"].values
    with run.contact(run.contact_passes()[0]) as ct:
        xc = ct["x_c"].values
        on_stretch = (xc >= x[0]) & (xc <= x[-1])
        creep = ct["creepage_x"].values[on_stretch]
    with run.pass_table() as ps:
        cpu = float(ps["cpu_seconds"].values.sum())
    return x, w, creep, cpu


def _creepage(path):
    """(x_c, creepage_x) of the steps with the patch centre on the recorded stretch."""
    run = Run.open(path)
    with run.rail() as rail:
        x = rail["x"].values
    with run.contact(run.contact_passes()[0]) as ct:
        xc = ct["x_c"].values
        on_stretch = (xc >= x[0]) & (xc <= x[-1])
        return xc[on_stretch], ct["creepage_x"].values[on_stretch]


def _harmonic(x, w, wavelength):
    """Complex amplitude of w at the wavelength over whole periods of x."""
    periods = math.floor((x[-1] - x[0]) / wavelength + 1e-9)
    keep = x <= x[0] + periods * wavelength - 0.5 * (x[1] - x[0])
    xs, ws = x[keep], w[keep]
    return 2.0 * np.mean(ws * np.exp(-2j * np.pi * xs / wavelength))


def _rel_l2(a, ref):
    if len(a) != len(ref):
        raise RunFileError(f"cannot compare histories of {len(a)} and {len(ref)} steps (different step length?)")
    norm = np.linalg.norm(ref)
    return float(np.linalg.norm(a - ref) / norm) if norm > 0 else math.nan


def pareto(points):
    """Indices of the (cost, error) points no other point beats in both."""
    front = []
    for i, (c, e) in enumerate(points):
        if not any((c2 <= c and e2 <= e) and (c2 < c or e2 < e) for j, (c2, e2) in enumerate(points) if j != i):
            front.append(i)
    return front


def evaluate(manifest_rows):
    """One result row per (scene, model, mesh), errors against the scene's reference."""
    groups = defaultdict(list)
    refs = {}
    for r in manifest_rows:
        groups[(r["scene"], r["model"], int(r["mesh"]))].append(r["file"])
        if int(r.get("reference", 0)):
            refs[r["scene"]] = r["file"]
    out = []
    for (scene, model, mesh), files in sorted(groups.items()):
        if scene not in refs:
            raise RunFileError(f"scene {scene}: no reference run in the manifest")
        rx, rw, _, _ = _curves(refs[scene])
        ref_xc, rc = _creepage(refs[scene])
        wavelength = _wavelength(refs[scene])
        h_ref = _harmonic(rx, rw, wavelength)
        x, w, creep, _ = _curves(files[0])
        cpu = float(np.median([_curves(f)[3] for f in files]))
        h = _harmonic(x, w, wavelength)
        phase = float(np.angle(h / h_ref)) if abs(h_ref) > 0 else math.nan
        out.append({
            "scene": scene, "model": model, "mesh": mesh, "repeats": len(files), "cpu_seconds": cpu,
            "wear_l2": _rel_l2(np.interp(rx, x, w), rw),
            "wear_fluct_l2": _rel_l2(np.interp(rx, x, w) - np.mean(np.interp(rx, x, w)), rw - np.mean(rw)),
            "harmonic_amp": float(abs(h) / abs(h_ref) - 1.0) if abs(h_ref) > 0 else math.nan,
            "harmonic_phase": phase, "creepage_l2": _rel_l2(np.interp(ref_xc, *_creepage(files[0])), rc),
            "pareto": 0,
        })
    for scene in {r["scene"] for r in out}:
        rows = [r for r in out if r["scene"] == scene and r["wear_l2"] > 0]
        for i in pareto([(r["cpu_seconds"], r["wear_l2"]) for r in rows]):
            rows[i]["pareto"] = 1
    return out


def chart(rows, path: Path, xlabel: str = "CPU time per passage (s)") -> Path:
    """Wear error against ``cpu_seconds`` per scene panel, Pareto front circled."""
    scenes = sorted({r["scene"] for r in rows})
    cols = min(2, len(scenes))
    nrows = math.ceil(len(scenes) / cols)
    fig = Figure(figsize=(6 * cols, 4.2 * nrows), layout="constrained")
    axes = np.atleast_1d(fig.subplots(nrows, cols, squeeze=False)).ravel()
    for ax, scene in zip(axes, scenes):
        mine = [r for r in rows if r["scene"] == scene and r["wear_l2"] > 0]
        for model in sorted({r["model"] for r in mine}):
            pts = sorted((r for r in mine if r["model"] == model), key=lambda r: r["mesh"])
            ax.loglog([p["cpu_seconds"] for p in pts], [p["wear_l2"] for p in pts],
                      marker=MARKERS.get(model, "x"), label=model)
            for p in pts:
                ax.annotate(f"{p['mesh']}", (p["cpu_seconds"], p["wear_l2"]), fontsize=7,
                            xytext=(3, 3), textcoords="offset points")
        front = sorted((r for r in mine if r["pareto"]), key=lambda r: r["cpu_seconds"])
        ax.plot([p["cpu_seconds"] for p in front], [p["wear_l2"] for p in front], "o", ms=11,
                mfc="none", mec="k", label="Pareto front")
        ax.set(title=scene, xlabel=xlabel, ylabel="centre-line wear error (rel. L2)")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    for ax in axes[len(scenes):]:
        ax.set_visible(False)
    fig.savefig(path, dpi=DPI)
    return path


def run(manifest: Path, out_dir: Path):
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = evaluate(read_csv(manifest))
    table = write_csv(out_dir / "speed_accuracy.csv", CSV_COLUMNS, rows)
    return rows, [table, chart(rows, out_dir / "speed_accuracy.png")]


def format_table(rows) -> str:
    lines = [f"{'scene':<26} {'model':<21} {'mesh':>4} {'cpu s':>8} {'wear L2':>8} {'fluct L2':>8} {'amp':>8} "
             f"{'phase':>8} {'creep L2':>8} P"]
    for r in rows:
        lines.append(f"{r['scene']:<26} {r['model']:<21} {r['mesh']:>4} {r['cpu_seconds']:>8.3f} "
                     f"{r['wear_l2']:>8.4f} {r['wear_fluct_l2']:>8.4f} {r['harmonic_amp']:>+8.4f} {r['harmonic_phase']:>+8.4f} "
                     f"{r['creepage_l2']:>8.4f} {'*' if r['pareto'] else ''}")
    return "\n".join(lines)
