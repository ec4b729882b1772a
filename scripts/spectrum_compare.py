"""How far two linear growth spectra of the same scene and classes are
apart (corrugation spectrum files, e.g. at two perturbation sizes): the
largest difference of the modes' growth rates (matched by the overlap
of their eigenvectors) and of the harmonics' diagonal
rates, in dB per 1e5 wheel passages, and the wavelength where each is
largest. With --by-wavelength the modes are matched by wavelength alone
and the diagonal rates by wavelength: a stretch of N identical bays
against one bay's N Bloch classes, whose classes are numbered
differently. With --csv, one line per pair for a table.

    python scripts/spectrum_compare.py A.h5 B.h5 [--csv] [--by-wavelength]
"""

import argparse
import pathlib
from collections import defaultdict

import numpy as np
import xarray as xr


def modes(ds: xr.Dataset, by_wavelength: bool) -> dict:
    """The modes' rates grouped by (class wavenumber, wavelength), sorted
    (for spectra whose harmonics are numbered differently)."""
    groups = defaultdict(list)
    for k, w, r in zip(ds.bloch_wavenumber.values, ds.wavelength.values, ds.growth_rate.values):
        groups[(0.0 if by_wavelength else round(float(k), 6), round(float(w), 9))].append(float(r))
    return {key: sorted(v) for key, v in groups.items()}


def diagonal(ds: xr.Dataset, by_wavelength: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The harmonics' diagonal rates sorted by signed wavenumber (by
    wavelength, one per wavelength: q and -q have the same rate), with
    their wavelengths."""
    q, r, w = ds.harmonic_wavenumber.values, ds.diagonal_rate.values, ds.harmonic_wavelength.values
    if by_wavelength:
        _, first = np.unique(np.round(np.abs(q), 6), return_index=True)
        q, r, w = np.abs(q[first]), r[first], w[first]
    order = np.argsort(q, kind="stable")
    return q[order], r[order], w[order]


def matched(a: xr.Dataset, b: xr.Dataset) -> list[tuple[int, int]]:
    """Pairs of modes (index in a, index in b) on the same harmonics,
    matched greedily by the overlap |v_a^H v_b| of their unit eigenvectors
    (largest first): a mode keeps its pairing when a perturbation changes
    which of its harmonics is largest."""
    va = a.vector_real.values + 1j * a.vector_imag.values
    vb = b.vector_real.values + 1j * b.vector_imag.values
    overlap = np.abs(va.conj() @ vb.T)
    pairs, used_a, used_b = [], set(), set()
    for flat in np.argsort(-overlap, axis=None):
        i, j = np.unravel_index(flat, overlap.shape)
        if i not in used_a and j not in used_b:
            pairs.append((int(i), int(j)))
            used_a.add(i)
            used_b.add(j)
    return pairs


def compare(a: xr.Dataset, b: xr.Dataset, by_wavelength: bool = False) -> dict:
    if a.sizes["mode"] != b.sizes["mode"]:
        raise SystemExit("the two spectra have different numbers of modes")
    worst, where = 0.0, None
    if by_wavelength:
        ma, mb = modes(a, by_wavelength), modes(b, by_wavelength)
        if ma.keys() != mb.keys() or any(len(ma[k]) != len(mb[k]) for k in ma):
            raise SystemExit("the two spectra have different classes or harmonics")
        for key in ma:
            for x, y in zip(ma[key], mb[key]):
                if abs(x - y) > worst:
                    worst, where = abs(x - y), key[1]
    else:
        if a.sizes["harmonic"] != b.sizes["harmonic"]:
            raise SystemExit("the two spectra perturb different harmonics")
        ra, rb, wl = a.growth_rate.values, b.growth_rate.values, a.wavelength.values
        for i, j in matched(a, b):
            if abs(ra[i] - rb[j]) > worst:
                worst, where = abs(ra[i] - rb[j]), float(wl[i])
    (qa, ra, wa), (qb, rb, _) = diagonal(a, by_wavelength), diagonal(b, by_wavelength)
    if qa.shape != qb.shape or not np.allclose(qa, qb, rtol=1e-9, atol=1e-9):
        raise SystemExit("the two spectra perturb different harmonics")
    d = np.abs(ra - rb)
    k = int(np.argmax(d))
    lead = (float(a.growth_rate[0]), float(b.growth_rate[0]), float(a.wavelength[0]))
    return {
        "modes": len(a.growth_rate),
        "mode_max": worst,
        "mode_at_mm": where * 1e3,
        "diag_max": float(d[k]),
        "diag_at_mm": float(wa[k]) * 1e3,
        "lead": lead,
    }


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("a", type=pathlib.Path)
    p.add_argument("b", type=pathlib.Path)
    p.add_argument("--csv", action="store_true")
    p.add_argument("--by-wavelength", action="store_true")
    args = p.parse_args()
    with xr.open_dataset(args.a, engine="h5netcdf", group="spectrum") as a, \
            xr.open_dataset(args.b, engine="h5netcdf", group="spectrum") as b:
        pa, pb = a.attrs["perturbation"], b.attrs["perturbation"]
        c = compare(a, b, args.by_wavelength)
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
