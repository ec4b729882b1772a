"""Comparison of growth studies (e.g. the same study at several traffic
scales m): rms corrugation and one harmonic's amplitude against traffic, and
a table of the harmonic's mean growth rate with its relative difference to
the first run, the largest update ratio and the final rms.

The harmonic is ``--wavelength`` (m), or by default the one of the first run
whose amplitude grew the most (in dB) over the run.  A file of two rails
gives a row and a curve per rail, labelled ``STEM (RAIL NAME)``.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from .figures import DPI
from .io import Run, RunFileError, root_attrs, write_csv

CSV_NAME = "growth_compare.csv"
CSV_COLUMNS = (
    "label", "file", "passes", "final_traffic", "max_traffic_scale", "max_update_ratio",
    "final_rms_m", "wavelength_m", "mean_growth_rate_db_per_1e5", "growth_rate_rel_diff",
)


# Harmonics whose initial amplitude is below this fraction of the largest
# have no meaningful rate in dB (they are built up from almost nothing).
STRONG = 0.1


@dataclass
class GrowthCurves:
    """What the comparison needs from one growth study."""

    label: str
    path: Path
    traffic: np.ndarray
    scale: np.ndarray
    rms: np.ndarray
    ratio: np.ndarray
    wavelengths: np.ndarray
    spectrum: np.ndarray  # (pass, wavelength), m
    initial: np.ndarray  # (wavelength,), m, before the first passage
    rail_name: str = ""  # the rail's name (the file's root or second_rail attribute)


def load_rails(path) -> list[GrowthCurves]:
    """The growth curves of every rail of a study (one for a one-rail file)."""
    return [_load(rail) for rail in Run.open(path).rails()]


def load(path) -> GrowthCurves:
    """The growth curves of a study's first rail."""
    return _load(Run.open(path))


def _load(run: Run) -> GrowthCurves:
    status = root_attrs(run.path).get("status", "complete")
    if status != "complete":
        raise RunFileError(f"{run.path}: status {status!r}: an unfinished study (resume it first)")
    with run.pass_table() as ps:
        for name in ("traffic", "traffic_scale", "rms_corrugation", "spectrum"):
            if name not in ps:
                raise RunFileError(f"{run.path}: {run.prefix}passes/{name} missing: not a growth study")
        ratio = ps["update_ratio"].values if "update_ratio" in ps else np.zeros(ps.sizes["pass"])
        # The contact-filtered spectrum (what the wheel sees; growth_rate is
        # computed on it) when the file has it.
        name = "filtered_spectrum" if "filtered_spectrum" in ps else "spectrum"
        spectrum, scale = ps[name].values, ps["traffic_scale"].values
        # growth_rate[0] = 20 log10(A_1 / A_0) 1e5 / m_0 gives back A_0.
        first_rate = ps["growth_rate"].values[0] if "growth_rate" in ps else np.zeros(spectrum.shape[1])
        initial = spectrum[0] / 10.0 ** (first_rate * scale[0] / 2e6)
        # A harmonic that started under the 1 pm floor has rate 0 there: no
        # initial amplitude to recover.
        initial = np.where((first_rate == 0.0) & (spectrum[0] > 0.0), np.nan, initial)
        label = f"{run.path.stem} ({run.rail_name})" if run.rail_name else run.path.stem
        return GrowthCurves(
            label=label, path=run.path, traffic=ps["traffic"].values,
            scale=ps["traffic_scale"].values, rms=ps["rms_corrugation"].values, ratio=ratio,
            wavelengths=ps["wavelength"].values, spectrum=spectrum, initial=initial, rail_name=run.rail_name or "",
        )


def fastest_growing(c: GrowthCurves) -> float:
    """Wavelength (m) whose amplitude grew the most (dB) over the run, among
    the harmonics of the initial roughness (at least 10 % of its largest):
    one built up from nothing has no meaningful rate in dB."""
    end = c.spectrum[-1]
    strong = c.initial >= STRONG * np.nanmax(c.initial)
    gain = np.where(strong & np.isfinite(c.initial),
                    np.log(np.maximum(end, 1e-300) / np.maximum(np.nan_to_num(c.initial), 1e-300)), -np.inf)
    return float(c.wavelengths[int(np.argmax(gain))])


def mean_rates(c: GrowthCurves) -> np.ndarray:
    """Mean growth rate of every harmonic (dB per 1e5 real passages) from the
    initial roughness to the end of the run; NaN where it is undefined."""
    a0, a1, span = c.initial, c.spectrum[-1], c.traffic[-1]
    ok = (a0 > 0) & (a1 > 0) & (span > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(ok, 20.0 * np.log10(a1 / a0) * 1e5 / span, np.nan)


def mean_rate(c: GrowthCurves, wavelength: float) -> float:
    """Mean growth rate of the harmonic nearest ``wavelength`` (dB per 1e5
    real passages) from the initial roughness to the end of the run."""
    return float(mean_rates(c)[int(np.argmin(np.abs(c.wavelengths - wavelength)))])


def compare_growth(paths, out_dir, wavelength: float | None = None):
    """Writes ``growth_compare.png`` and ``growth_compare.csv``; returns
    ``(rows, paths)``."""
    curves = [c for p in paths for c in load_rails(p)]
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    wl = wavelength if wavelength is not None else fastest_growing(curves[0])
    ref = mean_rate(curves[0], wl)
    rows = []
    for c in curves:
        rate = mean_rate(c, wl)
        rows.append({
            "label": c.label, "file": str(c.path), "passes": len(c.traffic),
            "final_traffic": float(c.traffic[-1]), "max_traffic_scale": float(c.scale.max()),
            "max_update_ratio": float(c.ratio.max()), "final_rms_m": float(c.rms[-1]),
            "wavelength_m": wl, "mean_growth_rate_db_per_1e5": rate,
            "growth_rate_rel_diff": (rate - ref) / abs(ref) if ref else float("nan"),
        })
    fig = Figure(figsize=(9, 7), layout="constrained")
    ax_rms, ax_amp = fig.subplots(2, 1, sharex=True)
    for c in curves:
        k = int(np.argmin(np.abs(c.wavelengths - wl)))
        label = f"{c.label} (max q = {c.ratio.max():.2g})"
        ax_rms.plot(c.traffic, c.rms * 1e6, "o-", ms=2, label=label)
        t = np.r_[0.0, c.traffic]
        ax_amp.plot(t, np.r_[c.initial[k], c.spectrum[:, k]] * 1e6, "o-", ms=2, label=label)
    ax_rms.set(ylabel="rms corrugation (µm)", title="Growth studies compared")
    ax_amp.set(xlabel="traffic (wheel passages)", ylabel=f"amplitude at {wl * 1e3:.1f} mm (µm)")
    for ax in (ax_rms, ax_amp):
        ax.grid(alpha=0.3)
    ax_rms.legend(fontsize=8)
    png = out_dir / "growth_compare.png"
    fig.savefig(png, dpi=DPI)
    return rows, [png, write_csv(out_dir / CSV_NAME, CSV_COLUMNS, rows)]


def format_table(rows) -> str:
    w = max([28] + [len(r["label"]) for r in rows])  # "STEM (RAIL NAME)" of a two-rail study
    head = f"{'run':<{w}} {'passes':>6} {'traffic':>10} {'max m':>9} {'max q':>7} {'rate dB/1e5':>12} {'rel diff':>9}"
    lines = [head]
    for r in rows:
        lines.append(
            f"{r['label']:<{w}} {r['passes']:>6} {r['final_traffic']:>10.3e} {r['max_traffic_scale']:>9.3g} "
            f"{r['max_update_ratio']:>7.3f} {r['mean_growth_rate_db_per_1e5']:>12.4f} {r['growth_rate_rel_diff']:>9.3f}"
        )
    return "\n".join(lines)
