"""Summary of scripts/irregular_spectrum.sh (book: docs/src/guide/irregular-track.md).

Reads out/irregular_spectrum/ (or the folder given): each spectrum file's
supports (the spans' spread) and its fastest-growing mode (rate,
wavelength, frequency, the envelope over the supports against mid-span,
and where the pattern is deepest: the place, its span (1 the first, after
the support at the stretch's start) and its share of the span). Prints a
Markdown table; writes summary.csv.
"""

import csv
import sys
from pathlib import Path

import h5py
import numpy as np


def fastest(path):
    """The spectrum's stretch spans' spread and its fastest mode."""
    with h5py.File(path) as f:
        g = f["spectrum"]
        supports = g["support"][:]
        spans = np.diff(np.append(supports, g.attrs["stretch"]))
        k = int(np.argmax(g["growth_rate"][:]))
        deepest = float(g["deepest"][k])
        span = int(np.searchsorted(supports, deepest, side="right")) - 1
        return {
            "span_std_mm": 1e3 * float(np.std(spans, ddof=1)) if len(spans) > 1 else 0.0,
            "rate_db_per_1e5": float(g["growth_rate"][k]),
            # The modes' `wavelength` as h5py names it (a variable named like
            # the forced pattern's dimension, docs/src/reference/spectrum-file.md).
            "wavelength_mm": 1e3 * float(g["_nc4_non_coord_wavelength"][k]),
            "frequency_hz": float(g["frequency"][k]),
            "support_ratio": float(g["support_ratio"][k]),
            "deepest_m": deepest,
            "deepest_span": span + 1,
            "deepest_in_span": float(g["deepest_in_span"][k]),
            "growing_modes": int(np.sum(g["growth_rate"][:] > 0.0)),
        }


def main(out):
    rows = []
    for path in sorted(Path(out).glob("spectrum_*.h5")):
        rows.append({"case": path.stem.removeprefix("spectrum_"), **fastest(path)})
    if not rows:
        sys.exit(f"no spectrum_*.h5 in {out}")
    keys = list(rows[0])
    with open(Path(out) / "summary.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    print("| " + " | ".join(keys) + " |")
    print("|" + "---|" * len(keys))
    for r in rows:
        print("| " + " | ".join(f"{v:.3g}" if isinstance(v, float) else str(v) for v in r.values()) + " |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out/irregular_spectrum")
