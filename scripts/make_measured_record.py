#!/usr/bin/env python3
"""Writes configs/records/synthetic_trolley.txt: a synthetic rail roughness
record laid out like a corrugation trolley's plain-text export (a few header
lines, then distance in m and displacement in um, one sample per 1 mm).

The record is 0.600 m long (five windows of the 0.120 m stretch of
configs/measured_rail.toml) and holds, in um:
  * three harmonics periodic on 0.120 m: 1.5 sin(2 pi x / 40 mm + 0.3),
    1.0 sin(2 pi x / 30 mm + 1.1), 0.6 sin(2 pi x / 15 mm + 2.0);
  * seeded Gaussian roughness, 0.3 um rms before smoothing (a 3-point moving
    average, as a trolley's anti-alias filter would leave it);
  * a slope of 2 um per metre (a trolley's drift);
  * two spikes, +25 um at 0.212 m (dirt) and -18 um at 0.433 m (a pit).
Standard library only, seeded: the file is the same on every run.

Usage: python3 scripts/make_measured_record.py [OUT]
"""
import math
import random
import sys

SPACING = 1e-3  # m
LENGTH = 0.600  # m
HARMONICS = [(1.5, 0.040, 0.3), (1.0, 0.030, 1.1), (0.6, 0.015, 2.0)]  # um, m, rad
NOISE = 0.3  # um rms before smoothing
SLOPE = 2.0  # um per m
SPIKES = {212: 25.0, 433: -18.0}  # sample index: um


def main(out):
    rng = random.Random(20261126)
    n = round(LENGTH / SPACING)
    noise = [rng.gauss(0.0, NOISE) for _ in range(n + 2)]
    lines = [
        "Corrugation record (synthetic, scripts/make_measured_record.py)",
        "Site: test stretch; rail: left; direction: increasing distance",
        "Sample interval: 1 mm",
        "Distance (m)\tDisplacement (um)",
    ]
    for k in range(n):
        x = k * SPACING
        h = sum(a * math.sin(2 * math.pi * x / w + p) for a, w, p in HARMONICS)
        h += (noise[k] + noise[k + 1] + noise[k + 2]) / 3.0
        h += SLOPE * x
        h += SPIKES.get(k, 0.0)
        lines.append(f"{x:.3f}\t{h:.3f}")
    with open(out, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "configs/records/synthetic_trolley.txt")
