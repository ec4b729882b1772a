"""The receptance figures of ``corrugation track`` files: magnitude and phase
of the rail point receptance above a sleeper and at mid-span (the discrete
model), the continuous model's, and the wheel and contact receptances, with
the resonances marked; with several wheels (``[vehicle]``) the transfer
receptances between them."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from .io import RunFileError


def load(path):
    try:
        ds = xr.open_dataset(path, engine="h5netcdf", group="track")
    except (OSError, ValueError) as err:
        raise RunFileError(f"{path}: not a track file (no group 'track'): {err}") from None
    for name in ("receptance_real", "receptance_imag", "frequency", "position"):
        if name not in ds.variables:
            raise RunFileError(f"{path}: group 'track' has no variable '{name}'")
    return ds


def figure(path, out):
    import matplotlib.pyplot as plt

    ds = load(path)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    f = ds["frequency"].values
    rec = ds["receptance_real"].values + 1j * ds["receptance_imag"].values
    cont = ds["continuous_receptance_real"].values + 1j * ds["continuous_receptance_imag"].values
    pos = ds["position"].values
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for i, label in ((0, "above a sleeper"), (len(pos) - 1, "mid-span")):
        ax.loglog(f, np.abs(rec[i]), label=f"discrete, {label} (x = {pos[i] * 1e3:.0f} mm)")
        bx.semilogx(f, np.degrees(np.angle(rec[i])))
    ax.loglog(f, np.abs(cont), "k--", label="continuous support")
    bx.semilogx(f, np.degrees(np.angle(cont)), "k--")
    ax.loglog(f, np.abs(ds["wheel_receptance"].values), ":", label="wheel")
    ax.axhline(float(ds["contact_receptance"].values), color="grey", ls="-.", label="contact spring")
    for key, name in (("pinned_pinned_hz", "pinned-pinned"), ("rail_on_pad_hz", "rail on pad"),
                      ("track_on_ballast_hz", "track on ballast")):
        if key in ds.attrs:
            ax.axvline(float(ds.attrs[key]), color="grey", lw=0.8)
            ax.text(float(ds.attrs[key]), ax.get_ylim()[1], name, rotation=90, va="top", fontsize=8)
    ax.set_ylabel("|receptance| (m/N)")
    ax.legend(fontsize=8)
    ax.set_title(f"{ds.attrs.get('rail', '')} track: point receptances (exp(+i w t))")
    bx.set_ylabel("phase (deg)")
    bx.set_xlabel("frequency (Hz)")
    fig.tight_layout()
    target = out / "track_receptance.png"
    fig.savefig(target, dpi=120)
    plt.close(fig)
    targets = [target]
    if "transfer_real" in ds.variables:
        targets.append(_transfer_figure(ds, out))
    return targets


def _transfer_figure(ds, out):
    """|transfer receptance| against frequency at each wheel distance: the
    discrete model with the force above a sleeper and at mid-span, the
    continuous model dashed."""
    import matplotlib.pyplot as plt

    f = ds["frequency"].values
    transfer = ds["transfer_real"] + 1j * ds["transfer_imag"]
    continuous = ds["continuous_transfer_real"] + 1j * ds["continuous_transfer_imag"]
    fig, ax = plt.subplots(figsize=(8, 5))
    for k, distance in enumerate(ds["distance"].values):
        colour = f"C{k % 10}"
        for source, style in zip(ds["source"].values, ("-", ":")):
            where = "above a sleeper" if source == 0 else "mid-span"
            ax.loglog(f, np.abs(transfer.sel(source=source, distance=distance).values), style, color=colour,
                      label=f"{distance:.2f} m, force {where}")
        ax.loglog(f, np.abs(continuous.sel(distance=distance).values), "--", color=colour, lw=0.8,
                  label=f"{distance:.2f} m, continuous support")
    ax.set(xlabel="frequency (Hz)", ylabel="|transfer receptance| (m/N)",
           title=f"{ds.attrs.get('rail', '')} track: rail displacement at a distance from a unit force")
    ax.legend(fontsize=8)
    fig.tight_layout()
    target = out / "track_transfer.png"
    fig.savefig(target, dpi=120)
    plt.close(fig)
    return target
