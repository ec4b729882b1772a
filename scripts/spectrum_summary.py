"""The book's table of linear growth spectra (corrugation spectrum files):
one markdown row per file with its fastest modes (wavelength, frequency,
rate; the nearest named resonance where one is within 10 %), its
least-damped mode in a frequency band (default the pinned-pinned band,
0.9-1.3 kHz) with its envelope over the sleeper against mid-span, and the
forced pattern's deepest harmonic of 10-150 mm (nm per 1e5 wheel
passages). On two rails each mode is named by the rail that holds most of
its energy.

    python scripts/spectrum_summary.py out/mechanism_spectra/*.h5 [--modes 3] [--band 900 1300]
"""

import argparse
import pathlib
import tomllib

import h5py
import numpy as np
import xarray as xr


def rail_names(path: pathlib.Path) -> tuple[str, str]:
    """The two rails' names of a two-rail scene (its [second_rail])."""
    with h5py.File(path, "r") as f:
        text = f.attrs["config"]
    config = tomllib.loads(text.decode() if isinstance(text, bytes) else str(text))
    second = config.get("second_rail", {})
    return second.get("first_name", "first rail"), second.get("name", "second rail")


def ratio_text(r: float) -> str:
    """A support ratio, large ones bounded (a mid-span node)."""
    return f"{r:.2f}" if r < 100 else "> 100"


def row(path: pathlib.Path, modes: int, band: tuple[float, float]) -> str:
    with xr.open_dataset(path, engine="h5netcdf", group="spectrum") as ds:
        share = ds.rail_share.values if "rail_share" in ds.variables else None
        names = rail_names(path) if share is not None else None

        def on(m: int) -> str:
            return "" if share is None else f", {names[0] if share[m] >= 0.5 else names[1]}"

        rate, wave, freq = ds.growth_rate.values, ds.wavelength.values * 1e3, ds.frequency.values
        ratio = ds.support_ratio.values
        labels = ds.resonance_label.values if "resonance_label" in ds.variables else []
        near = ds.near_resonance.values if "near_resonance" in ds.variables else np.full(len(rate), -1)
        fast = []
        for m in range(min(modes, len(rate))):
            name = f", {labels[near[m]]}" if near[m] >= 0 else ""
            fast.append(f"{wave[m]:.1f} mm ({freq[m]:.0f} Hz{name}{on(m)}) {rate[m]:+.2f}")
        if share is not None:
            other = np.flatnonzero(share < 0.5)
            if other.size and other[0] >= modes:
                m = other[0]
                fast.append(f"... {wave[m]:.1f} mm ({freq[m]:.0f} Hz{on(m)}) {rate[m]:+.2f}")
        inside = np.flatnonzero((freq >= band[0]) & (freq <= band[1]))
        if inside.size:
            k = inside[np.argmax(rate[inside])]
            pp = f"{wave[k]:.1f} mm ({freq[k]:.0f} Hz{on(k)}) {rate[k]:+.2f}, {ratio_text(ratio[k])}"
        else:
            pp = "none in the band"
        forced, fw = ds.forced_wear.values, ds.forced_wavelength.values
        keep = (fw >= 0.0099) & (fw <= 0.1501)
        j = np.flatnonzero(keep)[np.argmax(forced[keep])]
        depth = f"{fw[j] * 1e3:.1f} mm: {forced[j] * 1e5 * 1e9:.1f}"
    return f"| {path.stem} | {'; '.join(fast)} | {pp} | {depth} |"


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("files", nargs="+", type=pathlib.Path)
    p.add_argument("--modes", type=int, default=3)
    p.add_argument("--band", type=float, nargs=2, default=(900.0, 1300.0))
    a = p.parse_args()
    print("| case | fastest modes: wavelength (frequency) rate | least-damped mode of "
          f"{a.band[0]:.0f}-{a.band[1]:.0f} Hz, sleeper/mid-span | forced pattern's deepest harmonic (nm per 1e5) |")
    print("|---|---|---|---|")
    for f in a.files:
        print(row(f, a.modes, tuple(a.band)))


if __name__ == "__main__":
    main()
