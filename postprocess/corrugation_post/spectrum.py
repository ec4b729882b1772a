"""Figures and tables of ``corrugation spectrum`` files (the linear growth
spectrum): each mode's growth rate against its wavelength (wavelength
decreasing along the axis, the field's convention), coloured by its purity,
with the harmonics' rates alone beside; the forced pattern the smooth rail
wears; the fastest modes' envelopes along the stretch; and the forecast of
each band's level against traffic, where the file holds one."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import xarray as xr

from .io import RunFileError

# Modes whose envelope spectrum_envelope.png draws.
ENVELOPES = 4


def load(path):
    """The group ``spectrum`` of a spectrum file, as an xarray Dataset."""
    try:
        ds = xr.open_dataset(path, engine="h5netcdf", group="spectrum")
    except (OSError, ValueError) as err:
        raise RunFileError(f"{path}: not a spectrum file (no group 'spectrum'): {err}") from None
    for name in ("growth_rate", "wavelength", "frequency", "forced_wear", "forced_wavelength"):
        if name not in ds.variables:
            raise RunFileError(f"{path}: group 'spectrum' has no variable '{name}'")
    return ds


def table(ds, modes: int = 10):
    """The fastest ``modes`` modes as rows (dicts)."""
    rows = []
    for m in range(min(modes, ds.sizes["mode"])):
        rows.append({
            "mode": m,
            "growth_rate_db_per_1e5": float(ds.growth_rate[m]),
            "wavelength_mm": float(ds.wavelength[m]) * 1e3,
            "frequency_hz": float(ds.frequency[m]),
            "drift_mm_per_1e5": float(ds.drift[m]) * 1e3,
            "purity": float(ds.purity[m]),
            "support_ratio": float(ds.support_ratio[m]),
        })
    return rows


def figure(path, out):
    """Writes spectrum_modes.png, spectrum_forced.png, spectrum_envelope.png
    and spectrum_modes.csv into ``out``; returns their paths."""
    import matplotlib.pyplot as plt

    ds = load(path)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    targets = []
    lam = ds.wavelength.values * 1e3
    rate = ds.growth_rate.values
    fig, ax = plt.subplots(figsize=(8, 4.5))
    if "diagonal_rate" in ds.variables:
        hl = ds.harmonic_wavelength.values * 1e3
        positive = ds.harmonic_wavenumber.values > 0
        ax.plot(hl[positive], ds.diagonal_rate.values[positive], "_", color="grey", ms=10,
                label="each harmonic alone (J's diagonal)")
    sc = ax.scatter(lam, rate, c=ds.purity.values, cmap="viridis", vmin=0, vmax=1, zorder=3, label="modes")
    fig.colorbar(sc, ax=ax, label="purity (largest harmonic's share)")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xscale("log")
    ax.invert_xaxis()
    ax.set_xlabel("wavelength of the mode's largest harmonic (mm)")
    ax.set_ylabel("growth rate (dB per 1e5 wheel passages)")
    speed = ds.attrs.get("speed")
    title = f"linear growth spectrum: {ds.sizes['mode']} modes, {int(ds.attrs.get('bloch_classes', 1))} Bloch class(es)"
    if speed:
        title += f", {float(speed) * 3.6:.0f} km/h"
    ax.set_title(title)
    ax.legend(fontsize=8, loc="lower left")
    if speed:
        top = ax.secondary_xaxis("top", functions=(lambda l: float(speed) / np.maximum(l, 1e-9) * 1e3,
                                                   lambda f: float(speed) / np.maximum(f, 1e-9) * 1e3))
        top.set_xlabel("frequency (Hz)")
    fig.tight_layout()
    target = out / "spectrum_modes.png"
    fig.savefig(target, dpi=120)
    plt.close(fig)
    targets.append(target)

    fig, ax = plt.subplots(figsize=(8, 3.5))
    waves = ds.forced_wavelength.values * 1e3
    ax.semilogx(waves, ds.forced_wear.values * 1e5 * 1e9, ".-", label="forced (smooth rail)")
    ax.invert_xaxis()
    ax.set_xlabel("wavelength (mm)")
    ax.set_ylabel("wear per 1e5 wheel passages (nm)")
    ax.set_title("the forced pattern: what the smooth rail wears whatever the roughness")
    fig.tight_layout()
    target = out / "spectrum_forced.png"
    fig.savefig(target, dpi=120)
    plt.close(fig)
    targets.append(target)

    if "envelope" in ds.variables and ds.sizes["mode"] > 0:
        fig, ax = plt.subplots(figsize=(8, 3.5))
        x = ds.position.values * 1e3
        for m in range(min(ENVELOPES, ds.sizes["mode"])):
            ax.plot(x, ds.envelope.values[m], label=f"{lam[m]:.1f} mm, {rate[m]:+.2f} dB/1e5")
        ax.set_xlabel("position along the stretch (mm; a sleeper at 0 on a one-bay stretch)")
        ax.set_ylabel("local amplitude (rms 1)")
        ax.set_title("the fastest modes' patterns along the stretch")
        ax.legend(fontsize=8)
        fig.tight_layout()
        target = out / "spectrum_envelope.png"
        fig.savefig(target, dpi=120)
        plt.close(fig)
        targets.append(target)

    for group, name in (("forecast", "spectrum_forecast.png"), ("forecast_grinding", "spectrum_forecast_grinding.png")):
        target = forecast_figure(path, out, group, name)
        if target is not None:
            targets.append(target)

    rows = table(ds)
    target = out / "spectrum_modes.csv"
    with open(target, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()) if rows else ["mode"])
        w.writeheader()
        w.writerows(rows)
    targets.append(target)
    return targets


def forecast_figure(path, out, group="forecast", name="spectrum_forecast.png"):
    """``name``: each band's level against traffic from the file's ``group``
    (``forecast``: the config's bands and limit; ``forecast_grinding``: EN
    13231-3's bands against the grinding limit), each band's limit dashed
    in its colour and the linear horizon dotted; None where the file has no
    such group."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import h5py

    with h5py.File(path, "r") as f:
        if group not in f:
            return None
    fc = xr.open_dataset(path, engine="h5netcdf", group=group)
    traffic = fc.traffic.values
    mgt = float(fc.attrs["tonnes_per_passage"]) * 1e-6 if "tonnes_per_passage" in fc.attrs else None
    x = traffic * mgt if mgt else traffic
    fig, ax = plt.subplots(figsize=(8, 4.5))
    # One colour per band (tab20: twenty that can be told apart; ten would
    # repeat).
    colours = [plt.cm.tab20(k % 20) for k in range(fc.sizes["band"])]
    for b in range(fc.sizes["band"]):
        if str(fc.attrs.get("bands", "")).startswith("one-third"):
            label = f"{fc.band.values[b] * 1e3:.3g} mm"
        else:
            label = f"{fc.band_lower.values[b] * 1e3:.3g}-{fc.band_upper.values[b] * 1e3:.3g} mm"
        (line,) = ax.plot(x, fc.level_forecast.values[b], label=label, color=colours[b])
        limit = float(fc.limit_level.values[b])
        if np.isfinite(limit):
            ax.axhline(limit, color=line.get_color(), linestyle="--", linewidth=0.8)
    horizon = float(fc.attrs.get("horizon", np.inf))
    if np.isfinite(horizon):
        ax.axvline(horizon * mgt if mgt else horizon, color="grey", linestyle=":", label="linear horizon")
    # The levels up to 20 dB above the highest limit: the crossings, not
    # the linear regime's climb past any real roughness.
    levels = fc.level_forecast.values[np.isfinite(fc.level_forecast.values)]
    limits = fc.limit_level.values[np.isfinite(fc.limit_level.values)]
    if levels.size:
        top = float(levels.max())
        if limits.size:
            top = min(top, float(limits.max()) + 20.0)
        bottom = min(float(levels.min()), float(limits.min()) if limits.size else np.inf)
        ax.set_ylim(bottom - 3.0, top + 3.0)
    ax.set_xscale("log")
    ax.set_xlabel("traffic from now (MGT)" if mgt else "traffic from now (wheel passages)")
    ax.set_ylabel("band level (dB re 1 um)")
    ax.set_title(f"forecast from the spectrum\ndashed: each band's limit, {fc.attrs['limit_name']}", fontsize=10)
    ax.legend(fontsize=7, ncol=2, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    target = out / name
    fig.savefig(target, dpi=120)
    plt.close(fig)
    return target
