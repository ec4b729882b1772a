"""The mechanism study (``scripts/mechanism_study.sh``): each mechanism's
growth-rate spectra at its speeds, side by side, from the ``speeds.csv``
that ``corrugation-post speeds`` wrote for it (one folder per mechanism,
named after it). A mechanism that fixes a frequency puts its peak at one
frequency across speeds; one that fixes a wavelength, at one wavelength.

Writes ``mechanisms.png`` (one column per mechanism: growth rate against
frequency above, against wavelength below) and ``mechanisms_summary.csv``:
per mechanism and speed the fastest-growing harmonic and every harmonic
growing faster than ``GROWING`` dB per 1e5 passages.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from .figures import DPI
from .io import RunFileError, read_csv, write_csv
from .speeds import CSV_NAME, growth_rate_axes

SUMMARY_NAME = "mechanisms_summary.csv"
SUMMARY_COLUMNS = ("mechanism", "label", "speed_m_s", "peak_wavelength_m", "peak_frequency_hz",
                   "peak_rate_db_per_1e5", "growing")

# Rates above this (dB per 1e5 passages) count as growing in the summary.
GROWING = 0.1


def _load(folder: Path) -> dict[str, dict]:
    """The speeds.csv of one mechanism, by study label: speed, wavelength,
    frequency and rate arrays, and the rail's name (empty for one rail;
    older files have no ``rail`` column)."""
    path = folder / CSV_NAME
    if not path.is_file():
        raise RunFileError(f"{path}: no {CSV_NAME} (run `corrugation-post speeds` for this mechanism first)")
    studies: dict[str, dict[str, list[float]]] = {}
    for row in read_csv(path):
        s = studies.setdefault(row["label"], {"speed": [], "wavelength": [], "frequency": [], "rate": [],
                                              "rail": row.get("rail", "")})
        s["speed"].append(float(row["speed_m_s"]))
        s["wavelength"].append(float(row["wavelength_m"]))
        s["frequency"].append(float(row["frequency_hz"]))
        s["rate"].append(float(row["growth_rate_db_per_1e5"]))
    return {k: {n: v if n == "rail" else np.asarray(v) for n, v in s.items()} for k, s in studies.items()}


def mechanism_figure(folders, out_dir):
    """Writes ``mechanisms.png`` and ``mechanisms_summary.csv`` for the
    mechanisms in ``folders``; returns ``(rows, paths)``."""
    folders = [Path(f) for f in folders]
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    data = [(f.name, _load(f)) for f in folders]
    fig = Figure(figsize=(4 * len(data), 7), layout="constrained")
    axes = fig.subplots(2, len(data), sharey="col", squeeze=False)
    rows = []
    for col, (name, studies) in enumerate(data):
        ax_f, ax_wl = axes[0][col], axes[1][col]
        for label, s in sorted(studies.items(), key=lambda kv: kv[1]["speed"][0]):
            r = s["rate"]
            v = float(s["speed"][0])
            tag = f"{v * 3.6:.0f} km/h" + (f", {s['rail']}" if s["rail"] else "")
            ax_f.plot(s["frequency"], r, "o-", ms=3, label=tag)
            ax_wl.plot(s["wavelength"] * 1e3, r, "o-", ms=3, label=tag)
            ok = np.isfinite(r)
            k = int(np.nanargmax(np.where(ok, r, -np.inf))) if ok.any() else 0
            growing = [f"{w * 1e3:.1f} mm {g:+.2f}" for w, g in zip(s["wavelength"], r) if np.isfinite(g) and g > GROWING]
            rows.append({
                "mechanism": name, "label": label, "speed_m_s": v,
                "peak_wavelength_m": float(s["wavelength"][k]), "peak_frequency_hz": float(s["frequency"][k]),
                "peak_rate_db_per_1e5": float(r[k]) if ok.any() else float("nan"),
                "growing": "; ".join(growing),
            })
        ax_f.set(title=name, xlabel="frequency V / wavelength (Hz)", xscale="log")
        ax_wl.set(xlabel="wavelength (mm)", xscale="log")
        for ax in (ax_f, ax_wl):
            growth_rate_axes(ax)
    for ax in axes[:, 0]:
        ax.set_ylabel("mean growth rate (dB per 1e5 passages)")
    png = out_dir / "mechanisms.png"
    fig.savefig(png, dpi=DPI)
    return rows, [png, write_csv(out_dir / SUMMARY_NAME, SUMMARY_COLUMNS, rows)]


def format_table(rows) -> str:
    head = f"{'mechanism':<10} {'run':<14} {'km/h':>5} {'peak (mm)':>9} {'peak (Hz)':>9} {'dB/1e5':>7}  growing"
    lines = [head]
    for r in rows:
        lines.append(
            f"{r['mechanism']:<10} {r['label']:<14} {r['speed_m_s'] * 3.6:>5.0f} {r['peak_wavelength_m'] * 1e3:>9.1f} "
            f"{r['peak_frequency_hz']:>9.0f} {r['peak_rate_db_per_1e5']:>7.2f}  {r['growing']}"
        )
    return "\n".join(lines)
