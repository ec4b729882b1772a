"""The accuracy map behind ``contact.model = "auto"`` (``scripts/accuracy_map.sh``).

Input: a manifest CSV with columns ``wavelength, model, mesh, file``: runs of
one scene at several load wavelengths. Per wavelength the reference wear is the
Richardson extrapolation of the three finest exact-transient runs n1 < n2 < n3
with the observed order: ``w(n) = w_inf + c n^-p``, p from
``||w3 - w2|| / ||w2 - w1|| = (n2^-p - n3^-p) / (n1^-p - n2^-p)``, then
``w_ref = w3 + (w3 - w2) n3^-p / (n2^-p - n3^-p)``. Every run's error is the
relative L2 difference of its centre-line wear profile on the recorded stretch
``||w - w_ref|| / ||w_ref||``. ``lambda_over_2a`` uses the largest semi-axis
of the passage; ``cpu_per_step`` is the passage's CPU time per contact step.
Writes ``accuracy_map.csv`` with the columns of :data:`COLUMNS` and
``accuracy_map.png`` (error against CPU time per step, one panel per
wavelength, Pareto front circled).
"""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path

import numpy as np

from .io import Run, RunFileError, read_csv, write_csv
from .speed_accuracy import _curves, _rel_l2, chart, pareto

COLUMNS = ("model", "mesh", "wavelength", "lambda_over_2a", "wear_error", "cpu_per_step", "reference_order")

# The exact model on the fixed grid; its "mesh" is the element length in um.
FIXED = "exact-fixed"


def observed_order(n, d12: float, d23: float) -> float:
    """The order p of ``w(n) = w_inf + c n^-p`` from the differences of three
    meshes n = (n1, n2, n3): bisection on p in [0.1, 6]."""
    n1, n2, n3 = n
    target = d23 / d12

    def ratio(p):
        return (n2 ** -p - n3 ** -p) / (n1 ** -p - n2 ** -p)

    lo, hi = 0.1, 6.0
    if not ratio(hi) <= target <= ratio(lo):
        raise RunFileError(f"meshes {n}: difference ratio {target:.3f} is not that of a converging sequence")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ratio(mid) > target else (lo, mid)
    return 0.5 * (lo + hi)


def extrapolate(n, v1, v2, v3):
    """(v_inf, p): Richardson extrapolation of the values v1, v2, v3 on meshes
    n = (n1, n2, n3) with their observed order p."""
    n1, n2, n3 = n
    p = observed_order(n, float(np.linalg.norm(v2 - v1)), float(np.linalg.norm(v3 - v2)))
    return v3 + (v3 - v2) * n3 ** -p / (n2 ** -p - n3 ** -p), p


def reference_wear(runs):
    """(x, w_ref, p) from exact-transient runs [(n, file), ...] (three finest)."""
    (n1, f1), (n2, f2), (n3, f3) = sorted(runs)[-3:]
    x, w1, _, _ = _curves(f1)
    w2 = np.interp(x, *_curves(f2)[:2])
    w3 = np.interp(x, *_curves(f3)[:2])
    return (x, *extrapolate((n1, n2, n3), w1, w2, w3))


def _a_max_and_steps(path) -> tuple[float, int]:
    run = Run.open(path)
    with run.contact(run.contact_passes()[0]) as ct:
        a = ct["semi_axis_a"].values
    return float(np.max(a)), int(len(a))


def evaluate(manifest_rows) -> list[dict]:
    """One map row per (wavelength, model, mesh)."""
    by_wavelength = defaultdict(list)
    for r in manifest_rows:
        by_wavelength[float(r["wavelength"])].append((r["model"], int(r["mesh"]), r["file"]))
    out = []
    for wavelength, runs in sorted(by_wavelength.items()):
        # The reference: the fixed grid's three finest runs when there are
        # three (refinement 1/dx), else the adapted mesh's.
        exact = [(1.0 / m, f) for model, m, f in runs if model == FIXED]
        if len(exact) < 3:
            exact = [(m, f) for model, m, f in runs if model == "exact-transient"]
        if len(exact) < 3:
            raise RunFileError(f"wavelength {wavelength}: the reference needs three exact-transient runs")
        x, w_ref, order = reference_wear(exact)
        for model, mesh, f in sorted(runs):
            xr, w, _, cpu = _curves(f)
            a_max, steps = _a_max_and_steps(f)
            # Cost per 0.2 mm rolled: the fixed grid's step is its element.
            per_02mm = 200.0 / mesh if model == FIXED else 1.0
            out.append({
                "model": model, "mesh": mesh, "wavelength": wavelength,
                "lambda_over_2a": wavelength / (2.0 * a_max),
                "wear_error": _rel_l2(np.interp(x, xr, w), w_ref), "cpu_per_step": cpu / steps * per_02mm,
                "reference_order": order,
            })
    return out


def chart_rows(rows) -> list[dict]:
    """The map in the shape of :func:`speed_accuracy.chart` (ms per step)."""
    out = []
    for wavelength in sorted({r["wavelength"] for r in rows}):
        mine = [r for r in rows if r["wavelength"] == wavelength and r["wear_error"] > 0]
        scene = f"lambda = {1e3 * wavelength:.0f} mm, lambda / 2a_max = {mine[0]['lambda_over_2a']:.2f}"
        pts = [{"scene": scene, "model": r["model"], "mesh": r["mesh"], "cpu_seconds": 1e3 * r["cpu_per_step"],
                "wear_l2": r["wear_error"], "pareto": 0} for r in mine]
        for i in pareto([(p["cpu_seconds"], p["wear_l2"]) for p in pts]):
            pts[i]["pareto"] = 1
        out.extend(pts)
    return out


def run(manifest: Path, out_dir: Path):
    """Evaluates the manifest, writes the map CSV and chart; returns (rows, paths)."""
    rows = evaluate(read_csv(manifest))
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    table = write_csv(out_dir / "accuracy_map.csv", COLUMNS, rows)
    figure = chart(chart_rows(rows), out_dir / "accuracy_map.png", xlabel="CPU time per step (ms)")
    return rows, [table, figure]


def format_table(rows) -> str:
    lines = [f"{'model':22} {'mesh':>4} {'lambda':>7} {'l/2a':>6} {'wear err':>9} {'ms/step':>8}"]
    for r in rows:
        lines.append(f"{r['model']:22} {r['mesh']:>4} {1e3 * r['wavelength']:>5.0f}mm {r['lambda_over_2a']:>6.2f} "
                     f"{r['wear_error']:>9.4f} {1e3 * r['cpu_per_step']:>8.2f}")
    return "\n".join(lines)


GROWTH_COLUMNS = ("model", "mesh", "cpu_per_passage", "rate_error", "reference_order", "reference")


def _rates(path, band=(0.010, 0.040)):
    """Wavelengths in ``band`` and their growth rates in the last passage."""
    run = Run.open(path)
    with run.pass_table() as ps:
        wl = ps["wavelength"].values
        keep = (wl >= band[0]) & (wl <= band[1])
        rates = ps["growth_rate"].values[-1, keep]
        cpu = float(np.median(ps["cpu_seconds"].values))
    return wl[keep], rates, cpu


def _refinement(model: str, mesh: int) -> float:
    """Refinement measure: n for the adapted mesh, 1/dx for the fixed grid
    (``exact-fixed`` runs give the element length in um as ``mesh``)."""
    return 1.0 / mesh if model == FIXED else float(mesh)



def evaluate_growth(manifest_rows) -> list[dict]:
    """Growth-rate error of each run against the extrapolated exact rates:
    those of the fixed grid's three finest runs when the manifest has them
    (``exact-fixed``), else the adapted mesh's (``exact-transient``)."""
    runs = [(r["model"], int(r["mesh"]), r["file"]) for r in manifest_rows]
    base = FIXED if sum(model == FIXED for model, _, _ in runs) >= 3 else "exact-transient"
    exact = sorted((_refinement(model, m), f) for model, m, f in runs if model == base)[-3:]
    if len(exact) < 3:
        raise RunFileError("the growth reference needs three exact-transient (or exact-fixed) runs")
    (n1, f1), (n2, f2), (n3, f3) = exact
    ref, p = extrapolate((n1, n2, n3), *(_rates(f)[1] for f in (f1, f2, f3)))
    out = []
    for model, mesh, f in sorted(runs):
        _, rates, cpu = _rates(f)
        out.append({"model": model, "mesh": mesh, "cpu_per_passage": cpu,
                    "rate_error": _rel_l2(rates, ref), "reference_order": p, "reference": base})
    return out


def run_growth(manifest: Path, out_dir: Path):
    rows = evaluate_growth(read_csv(manifest))
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    return rows, [write_csv(out_dir / "growth_accuracy.csv", GROWTH_COLUMNS, rows)]


def format_growth(rows) -> str:
    lines = [f"{'model':22} {'mesh':>4} {'CPU s/passage':>14} {'rate error':>11}",
             *(f"{r['model']:22} {r['mesh']:>4} {r['cpu_per_passage']:>14.2f} {r['rate_error']:>11.4f}" for r in rows)]
    if rows:
        ref = "the fixed grid's three finest" if rows[0]["reference"] == FIXED else "exact 14/20/28"
        lines.append(f"reference: {ref} extrapolated with observed order {rows[0]['reference_order']:.2f}"
                     " (exact-fixed mesh: element length in um)")
    return "\n".join(lines)
