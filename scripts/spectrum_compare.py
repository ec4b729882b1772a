"""How far two linear growth spectra of the same scene and classes are
apart (corrugation spectrum files, e.g. at two perturbation sizes): the
largest difference of the modes' growth rates (matched by Bloch class and
wavelength, each group sorted by rate) and of the harmonics' diagonal
rates, in dB per 1e5 wheel passages, and the wavelength where each is
largest. With --csv, one line per pair for a table.

    python scripts/spectrum_compare.py A.h5 B.h5 [--csv]
"""

import argparse
import pathlib
from collections import defaultdict

import numpy as np
import xarray as xr


def modes(ds: xr.Dataset) -> dict:
    """The modes' rates grouped by (class wavenumber, wavelength), sorted."""
    groups = defaultdict(list)
    for k, w, r in zip(ds.bloch_wavenumber.values, ds.wavelength.values, ds.growth_rate.values):
        groups[(round(float(k), 6), round(float(w), 9))].append(float(r))
    return {key: sorted(v) for key, v in groups.items()}


def compare(a: xr.Dataset, b: xr.Dataset) -> dict:
    ma, mb = modes(a), modes(b)
    if ma.keys() != mb.keys() or any(len(ma[k]) != len(mb[k]) for k in ma):
        raise SystemExit("the two spectra have different classes or harmonics")
    worst, where = 0.0, None
    for key in ma:
        for x, y in zip(ma[key], mb[key]):
            if abs(x - y) > worst:
                worst, where = abs(x - y), key[1]
    if not np.allclose(a.harmonic_wavenumber.values, b.harmonic_wavenumber.values, rtol=0, atol=1e-9):
        raise SystemExit("the two spectra perturb different harmonics")
    d = np.abs(a.diagonal_rate.values - b.diagonal_rate.values)
    k = int(np.argmax(d))
    lead = (float(a.growth_rate[0]), float(b.growth_rate[0]), float(a.wavelength[0]))
    return {
        "modes": len(a.growth_rate),
        "mode_max": worst,
        "mode_at_mm": where * 1e3,
        "diag_max": float(d[k]),
        "diag_at_mm": float(a.harmonic_wavelength[k]) * 1e3,
        "lead": lead,
    }


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("a", type=pathlib.Path)
    p.add_argument("b", type=pathlib.Path)
    p.add_argument("--csv", action="store_true")
    args = p.parse_args()
    with xr.open_dataset(args.a, engine="h5netcdf", group="spectrum") as a, \
            xr.open_dataset(args.b, engine="h5netcdf", group="spectrum") as b:
        pa, pb = a.attrs["perturbation"], b.attrs["perturbation"]
        c = compare(a, b)
    if args.csv:
        print(f"{args.a.stem},{args.b.stem},{pa:g},{pb:g},{c['modes']},{c['mode_max']:.4f},{c['mode_at_mm']:.2f},"
              f"{c['diag_max']:.4f},{c['diag_at_mm']:.2f},{c['lead'][0]:+.4f},{c['lead'][1]:+.4f},{c['lead'][2]*1e3:.2f}")
    else:
        print(f"{args.a.name} ({pa:g} m) against {args.b.name} ({pb:g} m), {c['modes']} modes:")
        print(f"  modes' rates: largest difference {c['mode_max']:.4f} dB per 1e5 (at {c['mode_at_mm']:.2f} mm)")
        print(f"  diagonal rates: largest difference {c['diag_max']:.4f} dB per 1e5 (at {c['diag_at_mm']:.2f} mm)")
        print(f"  leading mode: {c['lead'][0]:+.4f} / {c['lead'][1]:+.4f} dB per 1e5 at {c['lead'][2]*1e3:.2f} mm")


if __name__ == "__main__":
    main()
