"""Each rail's fastest-growing harmonics of a growth study's run files
(scripts/mechanism_study.sh, cases low_rail and two_rails): per file and
rail, the study's mean growth rate of each harmonic of the contact-filtered
profile (the passages' rates weighted by their traffic, dB per 1e5 wheel
passages), its frequency at the study's speed, and the three fastest of
10-120 mm. CSV on standard output."""

from __future__ import annotations

import sys
import tomllib

import h5py
import numpy as np


def rails(f: h5py.File):
    """(name, group prefix) of each rail of the file."""
    if "second_rail" in f:
        return [(f.attrs["rail_name"], ""), (f["second_rail"].attrs["rail_name"], "second_rail/")]
    return [("rail", "")]


def main(paths: list[str]) -> None:
    print("file,rail,speed_km_h,rank,wavelength_mm,frequency_hz,rate_db_per_1e5,rate_120mm")
    for path in paths:
        with h5py.File(path, "r") as f:
            config = f.attrs["config"]
            speed = tomllib.loads(config if isinstance(config, str) else config.decode())["rolling"]["speed"]
            for name, prefix in rails(f):
                passes = f[prefix + "passes"]
                waves = passes["wavelength"][()]
                scale = passes["traffic_scale"][()]
                rate = (passes["growth_rate"][()] * scale[:, None]).sum(axis=0) / scale.sum()
                band = (waves >= 0.010 - 1e-9) & (waves <= 0.120 + 1e-9)
                at_120 = rate[np.argmin(abs(waves - 0.120))]
                order = [k for k in np.argsort(-rate) if band[k]][:3]
                for rank, k in enumerate(order, 1):
                    print(
                        f"{path.split('/')[-1]},{name},{speed * 3.6:.0f},{rank},{waves[k] * 1e3:.1f},"
                        f"{speed / waves[k]:.0f},{rate[k]:+.2f},{at_120:+.2f}"
                    )


if __name__ == "__main__":
    main(sys.argv[1:])
