"""Summary of scripts/irregular_track.sh (book: docs/src/guide/irregular-track.md).

Reads out/irregular_track/ (or the folder given): the track files'
mid-span receptances (each span's, and their mean over the spans) near the
pinned-pinned resonance, and the growth runs' fastest-growing harmonic of
the initial roughness (the run's own "what grew" line). Prints Markdown
tables; writes summary.csv.
"""

import csv
import re
import sys
from pathlib import Path

import h5py
import numpy as np

BAND_HZ = (700.0, 1500.0)


def mid_span(path):
    """(frequency, |receptance| at each mid-span (span, frequency))."""
    with h5py.File(path) as f:
        fr = f["track/frequency"][:]
        if "layout" in f:
            g = f["layout"]
            a = np.abs(g["receptance_real"][:] + 1j * g["receptance_imag"][:])[1::2]
            return fr, a
        t = f["track"]
        return fr, np.abs(t["receptance_real"][-1] + 1j * t["receptance_imag"][-1])[None, :]


def peak(fr, a):
    """The largest local peak of `a` in BAND_HZ: (frequency, value)."""
    k = [i for i in range(1, len(a) - 1) if BAND_HZ[0] <= fr[i] <= BAND_HZ[1] and a[i] >= a[i - 1] and a[i] >= a[i + 1]]
    i = max(k, key=lambda i: a[i]) if k else int(np.argmax(a))
    return fr[i], a[i]


def main(out):
    out = Path(out)
    rows = []
    base = None
    for path in sorted(out.glob("track_*.h5")):
        name = path.stem.removeprefix("track_")
        fr, a = mid_span(path)
        f_mean, mean_peak = peak(fr, a.mean(axis=0))
        spans = [peak(fr, s)[1] for s in a]
        row = {"case": name, "spans": len(a), "f_peak_hz": f_mean, "mean_peak": mean_peak, "largest_span_peak": max(spans)}
        run = out / f"run_{name}.txt"
        if run.exists():
            text = run.read_text()
            grew = re.search(r"what grew[^:]*: ([\d.]+) mm ([+-][\d.]+)", text)
            if grew:
                wl, rate = float(grew.group(1)) / 1000.0, float(grew.group(2))
                row.update(fastest_mm=wl * 1000.0, rate_db=rate)
        rows.append(row)
        if name == "uniform":
            base = mean_peak
    for r in rows:
        r["ratio"] = r["mean_peak"] / base if base else float("nan")
    keys = ["case", "spans", "f_peak_hz", "mean_peak", "ratio", "largest_span_peak", "fastest_mm", "rate_db"]
    with open(out / "summary.csv", "w", newline="") as f:
        w = csv.DictWriter(f, keys)
        w.writeheader()
        w.writerows(rows)
    print("| case | peak (Hz) | mean mid-span peak (m/N) | against uniform | largest span's peak (m/N) |")
    print("|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['case']} | {r['f_peak_hz']:.0f} | {r['mean_peak']:.3e} | {r['ratio']:.3f} | {r['largest_span_peak']:.3e} |")
    print()
    print("| standard deviation | seeds | mean peak against uniform: mean (min - max) |")
    print("|---|---|---|")
    for std in ("0.01", "0.02", "0.05"):
        v = [r["ratio"] for r in rows if r["case"].startswith(f"spacing_{std}_")]
        if v:
            print(f"| {float(std) * 100:.0f} cm | {len(v)} | {np.mean(v):.3f} ({min(v):.3f} - {max(v):.3f}) |")
    print()
    print("| case | fastest-growing harmonic of the initial roughness | rate (dB per 1e5) |")
    print("|---|---|---|")
    for r in rows:
        if "fastest_mm" in r:
            print(f"| {r['case']} | {r['fastest_mm']:.1f} mm | {r['rate_db']:+.2f} |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out/irregular_track")
