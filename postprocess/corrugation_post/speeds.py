"""Growth studies at several speeds and under mixed traffic
(``scripts/discrete_speeds.sh``): each harmonic's mean growth rate over the
study against wavelength and against frequency ``f = V / wavelength``, with
the track's resonances (a ``corrugation track`` file) marked. A mechanism
fixed in frequency puts the peak at one frequency across speeds, at a
wavelength that moves with V.

A mixed-traffic study (group ``traffic`` with several classes) is drawn
against wavelength beside the share-weighted mean of the single-speed rates
of the same classes, which is what the linear regime predicts: there each
harmonic evolves as ``dA/dn = -sum_c s_c c_c A``, so its rate is the
share-weighted mean of the classes' rates.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter, NullFormatter

from .figures import DPI
from .growth import STRONG, GrowthCurves, load_rails, mean_rates
from .io import RunFileError, open_group, parse_config, root_attrs, write_csv

CSV_NAME = "speeds.csv"
CSV_COLUMNS = ("label", "rail", "speed_m_s", "wavelength_m", "frequency_hz", "growth_rate_db_per_1e5",
               "predicted_db_per_1e5")
SUMMARY_NAME = "speeds_summary.csv"
SUMMARY_COLUMNS = ("label", "rail", "classes", "speed_m_s", "passes", "final_traffic", "final_rms_m",
                   "peak_wavelength_m", "peak_frequency_hz", "peak_rate_db_per_1e5", "rms_rate_diff_to_prediction")

# Speeds within this (m/s) are the same class speed.
SPEED_TOL = 0.01


@dataclass
class Study:
    """One rail of a growth study and the study's traffic classes."""

    curves: GrowthCurves
    speeds: np.ndarray  # (class,), m/s
    shares: np.ndarray  # (class,), 1
    names: list[str]
    rail: str = ""  # the rail's name in a two-rail file ("" for one rail)
    first: bool = True  # the file's first rail

    @property
    def label(self) -> str:
        return self.curves.label

    @property
    def mixed(self) -> bool:
        return len(self.speeds) > 1

    def rates(self) -> np.ndarray:
        """Mean growth rate per harmonic over the study (dB per 1e5 real
        passages); NaN where the initial amplitude is below STRONG of the
        largest."""
        a0 = self.curves.initial
        strong = np.isfinite(a0) & (a0 >= STRONG * np.nanmax(a0))
        return np.where(strong, mean_rates(self.curves), np.nan)


def load_studies(path) -> list[Study]:
    """Every rail of a growth study (one for a one-rail file), each with the
    study's traffic classes."""
    rails = load_rails(path)
    try:
        with open_group(path, "traffic") as t:
            speeds, shares = t["speed"].values, t["share"].values
            names = str(t.attrs.get("class_names", "")).split() or [f"class{i}" for i in range(len(speeds))]
    except (KeyError, RunFileError):
        # A file without classes: the config's speed.
        config = parse_config(root_attrs(path).get("config", ""), path)
        speeds, shares, names = np.array([float(config["rolling"]["speed"])]), np.array([1.0]), ["base"]
    named = len(rails) > 1
    return [Study(curves=c, speeds=np.asarray(speeds, float), shares=np.asarray(shares, float), names=names,
                  rail=c.rail_name if named else "", first=k == 0) for k, c in enumerate(rails)]


def predicted(mix: Study, singles: list[Study]) -> np.ndarray | None:
    """The share-weighted mean of the single-speed rates of the mix's
    classes (None when a class has no single-speed study; a mix has one
    rail: the singles' first rails)."""
    total = np.zeros_like(mix.curves.wavelengths)
    for v, s in zip(mix.speeds, mix.shares):
        match = [st for st in singles if st.first and abs(st.speeds[0] - v) <= SPEED_TOL
                 and np.array_equal(st.curves.wavelengths, mix.curves.wavelengths)]
        if not match:
            return None
        total = total + s * match[0].rates()
    return total


def _resonances(track) -> list[tuple[str, float]]:
    if track is None:
        return []
    with xr.open_dataset(track, engine="h5netcdf", group="track") as ds:
        attrs = dict(ds.attrs)
    names = (("pinned_pinned_hz", "pinned-pinned"), ("rail_on_pad_hz", "rail on pad"))
    return [(name, float(attrs[key])) for key, name in names if key in attrs]


def growth_rate_axes(ax) -> None:
    """A growth rate against a logarithmic wavelength or frequency: plain
    numbers on the axis, the zero line, the grid and the legend."""
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.axhline(0.0, color="black", lw=0.6)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)


def speed_study(paths, out_dir, track=None):
    """Writes ``speeds.png``, ``speeds.csv`` and ``speeds_summary.csv``;
    returns ``(rows, paths)`` with one summary row per study and rail (both
    rails of a two-rail study)."""
    studies = [st for p in paths for st in load_studies(p)]
    singles = [s for s in studies if not s.mixed]
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    resonances = _resonances(track)
    fig = Figure(figsize=(12, 5), layout="constrained")
    ax_wl, ax_f = fig.subplots(1, 2, sharey=True)
    rows, summary = [], []
    for st in studies:
        c = st.curves
        r = st.rates()
        wl = c.wavelengths
        pred = predicted(st, singles) if st.mixed else None
        v = float(np.sum(st.speeds * st.shares))
        label = st.label + (f" (mix {', '.join(f'{s * 3.6:.0f}' for s in st.speeds)} km/h)" if st.mixed
                            else f" ({st.speeds[0] * 3.6:.0f} km/h)")
        line, = ax_wl.plot(wl * 1e3, r, "o-", ms=3, label=label)
        if st.mixed:
            if pred is not None:
                ax_wl.plot(wl * 1e3, pred, ":", color=line.get_color(), lw=1.5,
                           label=f"{st.label}: share-weighted mean of the single speeds")
        else:
            ax_f.plot(st.speeds[0] / wl, r, "o-", ms=3, color=line.get_color(), label=label)
        for k in range(len(wl)):
            rows.append({
                "label": st.label, "rail": st.rail, "speed_m_s": v, "wavelength_m": float(wl[k]),
                "frequency_hz": float(v / wl[k]) if not st.mixed else float("nan"),
                "growth_rate_db_per_1e5": float(r[k]),
                "predicted_db_per_1e5": float(pred[k]) if pred is not None else float("nan"),
            })
        ok = np.isfinite(r)
        k = int(np.nanargmax(np.where(ok, r, -np.inf))) if ok.any() else 0
        diff = float("nan")
        if pred is not None:
            both = ok & np.isfinite(pred)
            diff = float(np.sqrt(np.mean((r[both] - pred[both]) ** 2))) if both.any() else float("nan")
        summary.append({
            "label": st.label, "rail": st.rail, "classes": " ".join(st.names), "speed_m_s": v, "passes": len(c.traffic),
            "final_traffic": float(c.traffic[-1]), "final_rms_m": float(c.rms[-1]),
            "peak_wavelength_m": float(wl[k]), "peak_frequency_hz": float(v / wl[k]) if not st.mixed else float("nan"),
            "peak_rate_db_per_1e5": float(r[k]) if ok.any() else float("nan"),
            "rms_rate_diff_to_prediction": diff,
        })
    for name, f in resonances:
        ax_f.axvline(f, color="grey", lw=0.8)
        ax_f.text(f, 1.0, f" {name} {f:.0f} Hz", rotation=90, va="top", fontsize=8,
                  transform=ax_f.get_xaxis_transform())
    ax_wl.set(xlabel="wavelength (mm)", ylabel="mean growth rate (dB per 1e5 passages)", xscale="log",
              title="Growth rate against wavelength")
    ax_f.set(xlabel="frequency V / wavelength (Hz)", xscale="log", title="Growth rate against frequency")
    for ax in (ax_wl, ax_f):
        growth_rate_axes(ax)
    png = out_dir / "speeds.png"
    fig.savefig(png, dpi=DPI)
    return summary, [png, write_csv(out_dir / CSV_NAME, CSV_COLUMNS, rows),
                     write_csv(out_dir / SUMMARY_NAME, SUMMARY_COLUMNS, summary)]


def format_table(rows) -> str:
    head = (f"{'run':<16} {'V (m/s)':>8} {'passes':>6} {'traffic':>10} {'rms (um)':>9} {'peak (mm)':>9} "
            f"{'peak (Hz)':>9} {'rate dB/1e5':>11} {'vs pred':>8}")
    lines = [head]
    for r in rows:
        lines.append(
            f"{r['label']:<16} {r['speed_m_s']:>8.2f} {r['passes']:>6} {r['final_traffic']:>10.3e} "
            f"{r['final_rms_m'] * 1e6:>9.3f} {r['peak_wavelength_m'] * 1e3:>9.2f} {r['peak_frequency_hz']:>9.0f} "
            f"{r['peak_rate_db_per_1e5']:>11.3f} {r['rms_rate_diff_to_prediction']:>8.3f}"
        )
    return "\n".join(lines)
