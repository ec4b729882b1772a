#!/usr/bin/env python3
"""Writes configs/records/wave50_texture.txt: a synthetic trolley record of a
50 mm corrugation wave in a rail's texture, laid out as
scripts/make_measured_record.py lays its record out (header lines, then
distance in m and displacement in um, one sample per 1 mm).

The record is 0.600 m long and holds, in um:
  * a 3 um (amplitude) wave of 50 mm: 12 periods, 2.12 um rms;
  * seeded Gaussian texture, a 3-point moving average of white noise
    scaled to 1 um rms (a trolley's anti-alias filter leaves it so).
Its 50 mm one-third-octave level is 20 lg(2.12) = 6.5 dB re 1 um plus the
texture's share. Standard library only, seeded: the same file every run.

Usage: python3 scripts/make_wave_record.py [OUT]
"""
import math
import random
import sys

SPACING = 1e-3  # m
LENGTH = 0.600  # m
WAVE = (3.0, 0.050)  # um amplitude, m wavelength
TEXTURE = 1.0  # um rms


def main(out):
    rng = random.Random(20261206)
    n = round(LENGTH / SPACING)
    white = [rng.gauss(0.0, 1.0) for _ in range(n + 2)]
    smooth = [(white[k] + white[k + 1] + white[k + 2]) / 3.0 for k in range(n)]
    mean = sum(smooth) / n
    rms = math.sqrt(sum((v - mean) ** 2 for v in smooth) / n)
    lines = [
        "Corrugation record (synthetic, scripts/make_wave_record.py)",
        "Site: test stretch; rail: left; direction: increasing distance",
        "Sample interval: 1 mm",
        "Distance (m)\tDisplacement (um)",
    ]
    for k in range(n):
        x = k * SPACING
        h = WAVE[0] * math.sin(2 * math.pi * x / WAVE[1]) + TEXTURE * (smooth[k] - mean) / rms
        lines.append(f"{x:.3f}\t{h:.4f}")
    with open(out, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "configs/records/wave50_texture.txt")
