"""The growth-rate map of a collected sweep (``corrugation sweep collect``).

Against one axis: the growth rate of every harmonic (against wavelength),
one curve per axis value, and the peak rate against the axis. Against two
axes: a map of the peak rate (the fastest-growing harmonic's, or the rate
of ``--wavelength``) with the peak's wavelength written in each cell.
``--y none`` draws against ``--x`` alone. Further axes are held at their
first value (``--at AXIS=INDEX`` picks another).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from .figures import DPI
from .growth import STRONG
from .io import RunFileError, write_csv

CSV_NAME = "sweep_map.csv"



def open_sweep(path) -> xr.Dataset:
    try:
        ds = xr.open_dataset(path, engine="h5netcdf")
    except (OSError, ValueError) as err:
        raise RunFileError(f"{path}: cannot open: {err}") from err
    if "growth_rate" not in ds or "wavelength" not in ds["growth_rate"].dims:
        ds.close()
        raise RunFileError(f"{path}: no growth_rate(..., wavelength): not a collected sweep")
    return ds


def _label(ds: xr.Dataset, dim: str) -> str:
    units = ds[dim].attrs.get("units", "")
    key = ds[dim].attrs.get("long_name", dim).replace("config key ", "").replace(" (sweep axis)", "")
    return f"{key} ({units})" if units and units != "1" else key


def sweep_map(path, out_dir, x: str | None = None, y: str | None = None, wavelength: float | None = None,
              at: dict[str, int] | None = None):
    """Writes ``sweep_map.png`` and ``sweep_map.csv``; returns ``(rows, paths)``."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    with open_sweep(path) as ds:
        axes = [d for d in ds["growth_rate"].dims if d != "wavelength"]
        one = y == "none"
        for name in (x, None if one else y):
            if name is not None and name not in axes:
                raise RunFileError(f"{path}: no sweep axis {name!r}; axes: {', '.join(axes)}")
        x = x or axes[0]
        y = None if one else (y if y is not None else next((a for a in axes if a != x), None))
        if y == x:
            raise RunFileError(f"--x and --y name the same axis {x!r}")
        held = {a: (at or {}).get(a, 0) for a in axes if a not in (x, y)}
        sel = ds.isel(held)
        rate = sel["growth_rate"]
        if wavelength is not None:
            peak = rate.sel(wavelength=wavelength, method="nearest")
            nearest = float(peak["wavelength"])
            peak_wl = xr.full_like(peak, nearest)
            what = f"growth rate at {nearest * 1e3:.1f} mm"
        else:
            # Among the harmonics of the initial roughness (at least STRONG of
            # its largest): one built up from nothing has no meaningful rate.
            if "initial_spectrum" in sel:
                initial = sel["initial_spectrum"]
                strong = initial >= STRONG * initial.max("wavelength")
                rate = rate.where(strong)
            filled = rate.fillna(-np.inf)
            idx = filled.argmax("wavelength")
            peak = rate.isel(wavelength=idx)
            peak_wl = ds["wavelength"].isel(wavelength=idx)
            what = "peak growth rate (fastest-growing harmonic of the roughness)"
        held_text = ", ".join(f"{a} = {ds[a].values[i]}" for a, i in held.items())
        title = what + (f" ({held_text})" if held_text else "")
        rows = []
        if y is None:
            fig = Figure(figsize=(11, 4.5), layout="constrained")
            ax_c, ax_p = fig.subplots(1, 2)
            for i, v in enumerate(ds[x].values):
                ax_c.plot(ds["wavelength"].values * 1e3, rate.isel({x: i}).values, "o-", ms=2, label=f"{v}")
            ax_c.set(xscale="log", xlabel="wavelength (mm)", ylabel="growth rate (dB per 1e5 passages)",
                     title="growth rate of each harmonic")
            ax_c.legend(title=_label(ds, x), fontsize=8)
            ax_p.plot(ds[x].values, peak.values, "o-")
            ax_p.set(xlabel=_label(ds, x), ylabel="dB per 1e5 passages", title=title)
            for i, v in enumerate(ds[x].values):
                rows.append({x: v, "rate_db_per_1e5": float(peak.values[i]),
                             "wavelength_m": float(np.asarray(peak_wl.values)[i])})
            for ax in (ax_c, ax_p):
                ax.grid(alpha=0.3)
                ax.axhline(0.0, color="black", lw=0.6)
        else:
            grid = peak.transpose(y, x).values
            wl = np.asarray(peak_wl.transpose(y, x).values) if peak_wl.ndim == 2 else np.broadcast_to(peak_wl.values,
                                                                                                       grid.shape)
            fig = Figure(figsize=(8, 6), layout="constrained")
            ax = fig.subplots()
            lim = np.nanmax(np.abs(grid)) if np.isfinite(grid).any() else 1.0
            im = ax.imshow(grid, origin="lower", aspect="auto", cmap="RdBu_r", vmin=-lim, vmax=lim)
            fig.colorbar(im, ax=ax, label="dB per 1e5 passages")
            ax.set_xticks(range(len(ds[x])), [f"{v:g}" if isinstance(v, float) else str(v) for v in ds[x].values])
            ax.set_yticks(range(len(ds[y])), [f"{v:g}" if isinstance(v, float) else str(v) for v in ds[y].values])
            ax.set(xlabel=_label(ds, x), ylabel=_label(ds, y), title=title)
            for j in range(grid.shape[0]):
                for i in range(grid.shape[1]):
                    if np.isfinite(grid[j, i]):
                        ax.text(i, j, f"{grid[j, i]:+.2f}\n{wl[j, i] * 1e3:.1f} mm", ha="center", va="center",
                                fontsize=8)
                    else:
                        ax.text(i, j, "missing", ha="center", va="center", fontsize=8)
                    rows.append({x: ds[x].values[i], y: ds[y].values[j], "rate_db_per_1e5": float(grid[j, i]),
                                 "wavelength_m": float(wl[j, i])})
        png = out_dir / "sweep_map.png"
        fig.savefig(png, dpi=DPI)
        columns = [c for c in (x, y) if c is not None] + ["rate_db_per_1e5", "wavelength_m"]
        return rows, [png, write_csv(out_dir / CSV_NAME, columns, rows)]


def format_table(rows) -> str:
    if not rows:
        return "(no members)"
    keys = list(rows[0].keys())
    lines = ["  ".join(f"{k:>22}" for k in keys)]
    for r in rows:
        lines.append("  ".join(f"{r[k]:>22.6g}" if isinstance(r[k], (float, np.floating)) else f"{str(r[k]):>22}"
                               for k in keys))
    return "\n".join(lines)
