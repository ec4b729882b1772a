"""The book's tables of the curving study (scripts/curving_study.sh): the
steady state of each curve (radius, speed, cant) for the leading and
trailing wheelsets, and each spectrum's fastest-growing mode, overall and
of the short pitch (20-100 mm).

    python scripts/curving_summary.py out/curving_study
"""

import pathlib
import re
import sys

import h5py
import numpy as np


def steady(path: pathlib.Path) -> list[str]:
    """Rows of one steady-state file: one per wheelset and rail."""
    with h5py.File(path, "r") as f:
        c = f["curving"]
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in c["wheel"][...]]
        radius, speed = c.attrs["radius_m"], c.attrs["speed_m_per_s"]
        cant, deficiency = c.attrs["cant_m"], c.attrs["cant_deficiency_m"]
        rows = []
        for i, name in enumerate(names):
            v = {k: float(c[k][i]) for k in ("normal_force", "creepage_x", "creepage_y", "spin",
                                              "lateral_shift", "angle_of_attack", "contact_angle")}
            flange = int(c["flange_contact"][i])
            rows.append(
                f"| {radius:.0f} | {speed * 3.6:.0f} | {cant * 1e3:.0f} ({deficiency * 1e3:.0f}) | {name} "
                f"| {v['normal_force'] / 1e3:.1f} | {v['creepage_x']:.2e} | {v['creepage_y']:.2e} "
                f"| {v['spin']:.3f} | {v['lateral_shift'] * 1e3:+.2f} | {v['angle_of_attack'] * 1e3:+.2f} "
                f"| {np.degrees(v['contact_angle']):.1f} | {'yes' if flange else 'no'} |"
            )
        return rows


def fastest(path: pathlib.Path) -> str:
    """The fastest-growing mode of a spectrum file: wavelength, frequency,
    rate (the modes' wavelength is stored beside the dimension of the same
    name, as netCDF-4 names a non-coordinate variable)."""
    with h5py.File(path, "r") as f:
        g = f["spectrum"]
        rate = np.asarray(g["growth_rate"][...], dtype=float)
        wavelength = np.asarray(g["_nc4_non_coord_wavelength"][...], dtype=float)
        frequency = np.asarray(g["frequency"][...], dtype=float)
        k = int(np.nanargmax(rate))
        short = np.where((wavelength >= 0.02) & (wavelength <= 0.1), rate, -np.inf)
        j = int(np.argmax(short))
        return (f"{wavelength[k] * 1e3:.1f} mm, {frequency[k]:.0f} Hz | {rate[k]:+.2f} "
                f"| {wavelength[j] * 1e3:.1f} mm, {frequency[j]:.0f} Hz | {rate[j]:+.2f}")


def main() -> None:
    out = pathlib.Path(sys.argv[1])
    print("| R (m) | V (km/h) | cant (deficiency) mm | wheel | N (kN) | creep x | creep y | spin (1/m) "
          "| shift (mm) | AoA (mrad) | angle (deg) | flange |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    key = lambda p: [int(x) for x in re.findall(r"\d+", p.stem)]
    for path in sorted(out.glob("steady_*.h5"), key=key):
        for row in steady(path):
            print(row)
    spectra = sorted(out.glob("spectrum_*.h5"), key=lambda p: (key(p), p.stem))
    if spectra:
        print()
        print("| spectrum (R, wheelset, rail) | fastest mode | rate (dB per 1e5) | fastest of 20-100 mm | rate |")
        print("|---|---|---|---|---|")
        for path in spectra:
            print(f"| {path.stem.removeprefix('spectrum_')} | {fastest(path)} |")


if __name__ == "__main__":
    main()
