#!/usr/bin/env python3
"""Compares two run files of the same study: the largest difference of the
recorded normal force (first recorded passage) and of the rail's profile,
each relative to its largest magnitude, and the largest difference of the
growth rates (dB per 1e5 wheel passages) over the harmonics that carry at
least 1 % of the spectrum's largest amplitude (the rates of emptier ones,
hundreds of dB per 1e5 where the sleepers feed them, move with any rounding
of the profile), at the first and the last
passage. Prints one line:
    CONFIG  force_rel  profile_rel  rates_first_dB  rates_last_dB
Usage: model_diff.py NAME A.h5 B.h5
"""
import sys

import h5py
import numpy as np


def rel(x, y):
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    scale = max(np.abs(x).max(), np.abs(y).max())
    return np.abs(x - y).max() / scale if scale > 0 else 0.0


def main():
    name, a_path, b_path = sys.argv[1:4]
    with h5py.File(a_path, "r") as a, h5py.File(b_path, "r") as b:
        passes = sorted(k for k in a.get("contact", {}).keys())
        force = max((rel(a[f"contact/{p}/normal_force"][()], b[f"contact/{p}/normal_force"][()]) for p in passes[:1]),
                    default=float("nan"))
        profile = rel(a["rail/state"][()], b["rail/state"][()])
        ra, rb = a["passes/growth_rate"][()], b["passes/growth_rate"][()]
        spectrum = a["passes/spectrum"][()]
        worst = []
        for p in (0, ra.shape[0] - 1):
            held = (spectrum[p] >= 1e-2 * spectrum[p].max()) & np.isfinite(ra[p]) & np.isfinite(rb[p])
            worst.append(np.abs(ra[p][held] - rb[p][held]).max() if held.any() else float("nan"))
    print(f"{name:24s} {force:10.1e} {profile:11.1e} {worst[0]:14.1e} {worst[1]:13.1e}")


if __name__ == "__main__":
    main()
