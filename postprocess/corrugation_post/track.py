"""The receptance figure of ``corrugation track`` files: magnitude and phase
of the rail point receptance above a sleeper and at mid-span (the discrete
model), the continuous model's, and the wheel and contact receptances, with
the resonances marked."""

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
    return [target]
