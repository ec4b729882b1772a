"""The fastest modes of linear growth spectra (corrugation spectrum files),
one CSV row per file and mode: the file's stem, the mode's rank, growth
rate (dB per 1e5 wheel passages), wavelength (mm), frequency (Hz), drift
(mm per 1e5 wheel passages), purity, the envelope over the sleeper against
mid-span, and the file's deepest forced-pattern harmonic (mm, nm per 1e5
wheel passages).

    python scripts/spectrum_table.py out/x/*.h5 [--modes 5]
"""

import argparse
import csv
import pathlib
import sys

import numpy as np
import xarray as xr


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("files", nargs="+", type=pathlib.Path)
    p.add_argument("--modes", type=int, default=5)
    a = p.parse_args()
    w = csv.writer(sys.stdout)
    w.writerow(["case", "rank", "rate_db_per_1e5", "wavelength_mm", "frequency_hz", "drift_mm_per_1e5",
                "purity", "sleeper_over_midspan", "near_resonance", "forced_peak_mm", "forced_peak_nm_per_1e5"])
    for f in a.files:
        ds = xr.open_dataset(f, engine="h5netcdf", group="spectrum")
        forced = ds.forced_wear.values
        waves = ds.forced_wavelength.values
        k = int(np.argmax(np.where(waves <= 0.15, forced, 0.0)))
        labels = ds.resonance_label.values if "resonance_label" in ds.variables else []
        freqs = ds.resonance.values if "resonance" in ds.variables else []
        for m in range(min(a.modes, ds.sizes["mode"])):
            near = int(ds.near_resonance[m]) if "near_resonance" in ds.variables else -1
            name = f"{labels[near]} ({freqs[near]:.0f} Hz)" if near >= 0 else ""
            w.writerow([
                f.stem, m,
                f"{float(ds.growth_rate[m]):+.3f}",
                f"{float(ds.wavelength[m]) * 1e3:.2f}",
                f"{float(ds.frequency[m]):.0f}",
                f"{float(ds.drift[m]) * 1e3:+.3f}",
                f"{float(ds.purity[m]):.2f}",
                f"{float(ds.support_ratio[m]):.2f}",
                name,
                f"{waves[k] * 1e3:.1f}",
                f"{forced[k] * 1e5 * 1e9:.2f}",
            ])


if __name__ == "__main__":
    main()
