#!/usr/bin/env python3
"""The measured-rail guide's numbers from its runs (scripts/measured_windows.sh).

Usage: measured_windows.py WINDOW_0.h5 [WINDOW.h5 ...]

Prints the first run's rms after its first and last passage and the traffic,
its wall time (from WINDOW.time beside it, where present), and per harmonic
of the centre line (those above 0.1 um after the first passage in some
window, strongest first) the amplitude after the first passage and the mean
roughness-driven growth rate over the study (dB per 1e5 wheel passages),
as ranges over the windows, with their spread.
"""
import os
import sys

import h5py
import numpy as np


def main(files):
    runs = []
    for path in files:
        with h5py.File(path, "r") as f:
            p = f["passes"]
            runs.append(
                {
                    "rms": p["rms_corrugation"][:],
                    "traffic": p["traffic"][:],
                    "spectrum": p["spectrum"][:],
                    "rate": p["growth_rate"][:],
                    "wavelength": p["wavelength"][:],
                }
            )
    first = runs[0]
    timing = os.path.splitext(files[0])[0] + ".time"
    wall = open(timing).read().strip() if os.path.exists(timing) else "?"
    print(
        f"window 0: rms {first['rms'][0] * 1e6:.3f} um after the first passage, "
        f"{first['rms'][-1] * 1e6:.3f} um after {first['traffic'][-1]:.3g} wheel passages; {wall}"
    )
    strongest = np.max([r["spectrum"][0] for r in runs], axis=0)
    order = [k for k in np.argsort(-strongest) if strongest[k] > 1e-7]
    print("| wavelength | amplitude after the first passage, windows (um) | growth rate, windows | spread |")
    print("| --- | --- | --- | --- |")
    for k in order:
        amp = [r["spectrum"][0][k] * 1e6 for r in runs]
        rate = [float(np.mean(r["rate"][:, k])) for r in runs]
        w = first["wavelength"][k] * 1e3
        print(
            f"| {w:.3g} mm | {min(amp):.2f} .. {max(amp):.2f} | {min(rate):+.2f} .. {max(rate):+.2f} "
            f"| {max(rate) - min(rate):.2f} |"
        )


if __name__ == "__main__":
    main(sys.argv[1:])
