#!/usr/bin/env python3
"""The forecast of scripts/forecast_stretch.sh, stretch by stretch.

Usage: forecast_stretch.py RECORD SPECTRUM.h5 [SPECTRUM.h5 ...]

Prints, per band of each forecast group (`forecast`: one-third octaves
against the config's limit; `forecast_grinding`: EN 13231-3's bands against
the grinding limit), the level now and the wheel passages to the limit on
every stretch, and their spread; and the record's own one-third-octave
level of each band (its whole detrended record, rectangular window: the
record holds whole periods of its 50 mm wave), against which each
stretch's level is checked. A crossing beyond the file's linear horizon
(attribute `horizon`: the roughness grown tenfold) is marked `*`, an
extrapolation. Exits non-zero where a 50 mm level is more than 0.5 dB off
the record's or a finite traffic to a limit within the horizon spreads by
more than 10 %.
"""
import sys

import h5py
import numpy as np


def record_levels(path):
    """One-third-octave levels (dB re 1 um) of the whole record, by nominal
    centre (m)."""
    rows = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            parts = line.split()
            try:
                rows.append((float(parts[0]), float(parts[1])))
            except (ValueError, IndexError):
                continue
    x, h = np.array(rows).T
    h = h * 1e-6
    h = h - np.polyval(np.polyfit(x, h, 1), x)
    n = len(h)
    spacing = (x[-1] - x[0]) / (n - 1)
    c = np.fft.rfft(h) / n
    ms = 2.0 * np.abs(c) ** 2
    wavelength = np.full(len(c), np.inf)
    wavelength[1:] = n * spacing / np.arange(1, len(c))
    levels = {}
    for k in range(0, 31):
        centre = 10 ** (-k / 10)
        lo, hi = centre * 10 ** -0.05, centre * 10 ** 0.05
        inside = (wavelength >= lo) & (wavelength < hi)
        if centre <= n * spacing / 4 and inside.any():
            levels[round(centre, 6)] = 10 * np.log10(ms[inside].sum() / 1e-12)
    return levels


def main(record, files):
    ok = True
    own = record_levels(record)
    for group in ["forecast", "forecast_grinding"]:
        tables = []
        for path in files:
            with h5py.File(path, "r") as f:
                g = f[group]
                s = f["spectrum"]
                name = f"{s.attrs['stretch'] * 1e3:.0f} mm x {int(s.attrs['bloch_classes'])}"
                rows = {
                    round(float(b), 6): (float(l), float(p), float(lim))
                    for b, l, p, lim in zip(g["band"][:], g["level"][:], g["passages_to_limit"][:], g["limit_level"][:])
                }
                tables.append((name, rows, g.attrs["limit_name"], float(g.attrs["horizon"])))
        horizons = ", ".join(f"{t[3]:.3g}" for t in tables)
        print(f"{group}: against the {tables[0][2]}; linear horizons {horizons} wheel passages (* beyond)")
        bands = sorted(set().union(*[t[1].keys() for t in tables]), reverse=True)
        header = "  band      record " + "".join(f"| {t[0]:>24} " for t in tables) + "| spread"
        print(header)
        for b in bands:
            ref = own.get(min(own, key=lambda c: abs(np.log(c / b)))) if group == "forecast" else None
            cells, passages, levels, beyond = [], [], [], False
            for _, rows, _, horizon in tables:
                if b not in rows:
                    cells.append(f"| {'-':>24} ")
                    continue
                level, p, _ = rows[b]
                levels.append(level)
                passages.append(p)
                star = "*" if np.isfinite(p) and p > horizon else " "
                beyond |= star == "*"
                cells.append(f"| {level:6.2f} dB {p:12.3e}{star} ")
            finite = [p for p in passages if np.isfinite(p) and p > 0]
            spread = ""
            if len(finite) == len(passages) and len(finite) > 1:
                r = max(finite) / min(finite) - 1
                spread = f"{100 * r:5.1f} %"
                ok &= r <= 0.10 or beyond
            elif finite and len(finite) != len(passages):
                spread = "mixed"
            reference = f"{ref:6.2f}" if ref is not None else "     -"
            print(f"  {b * 1e3:7.1f} mm {reference} " + "".join(cells) + f"| {spread}")
            if group == "forecast" and abs(b - 0.05) < 1e-3 and ref is not None:
                worst = max(abs(l - ref) for l in levels)
                print(f"  50 mm band: the stretches' levels within {worst:.2f} dB of the record's own")
                ok &= worst <= 0.5 and len(levels) == len(tables)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2:]))
