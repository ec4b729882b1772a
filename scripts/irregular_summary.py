"""Summary of scripts/irregular_track.sh (book: docs/src/guide/irregular-track.md).

Reads out/irregular_track/ (or the folder given): the track files'
mid-span receptances (each span's, and their mean over the spans) near the
pinned-pinned resonance, and the growth runs' fastest-growing pattern (the
run's own "what grew" line) with where along the span it grows fastest
(the local rate -<w, r> / <r, r> of the last passage's wear w against the
profile r, both band-passed about the pattern's wavelength, binned by the
place in the span). Prints Markdown tables; writes summary.csv.
"""

import csv
import re
import sys
from pathlib import Path

import h5py
import numpy as np

BAND_HZ = (700.0, 1500.0)
BINS = 5


def mid_span(path):
    """(frequency, |receptance| at each mid-span (span, frequency), supports (m), period (m))."""
    with h5py.File(path) as f:
        fr = f["track/frequency"][:]
        if "layout" in f:
            g = f["layout"]
            a = np.abs(g["receptance_real"][:] + 1j * g["receptance_imag"][:])[1::2]
            return fr, a, g["support"][:], float(g.attrs["period"])
        t = f["track"]
        a = np.abs(t["receptance_real"][-1] + 1j * t["receptance_imag"][-1])[None, :]
        d = 2.0 * float(t["position"][-1])
        return fr, a, np.array([0.0]), d


def peak(fr, a):
    """The largest local peak of `a` in BAND_HZ: (frequency, value)."""
    k = [i for i in range(1, len(a) - 1) if BAND_HZ[0] <= fr[i] <= BAND_HZ[1] and a[i] >= a[i - 1] and a[i] >= a[i + 1]]
    i = max(k, key=lambda i: a[i]) if k else int(np.argmax(a))
    return fr[i], a[i]


def band(v, dx, lo, hi):
    """`v` (periodic) band-passed to wavelengths in [lo, hi]."""
    s = np.fft.rfft(v)
    k = np.arange(len(s))
    wl = np.where(k > 0, len(v) * dx / np.maximum(k, 1), np.inf)
    s[(wl < lo) | (wl > hi)] = 0.0
    return np.fft.irfft(s, len(v))


def where_fastest(run, supports, period, wavelength):
    """The local growth rate (1/passage, scaled) of the band about `wavelength` per place in the span."""
    with h5py.File(run) as f:
        x = f["rail/x"][:]
        mid = f["rail/y"].shape[0] // 2
        r = f["rail/profile"][-1, mid, :]
        w = f["rail/wear"][-1, mid, :]
    dx = x[1] - x[0]
    rb, wb = band(r, dx, wavelength / 1.25, wavelength * 1.25), band(w, dx, wavelength / 1.25, wavelength * 1.25)
    bounds = np.append(supports, period)
    u = np.mod(x - x[0], period)
    m = np.searchsorted(bounds, u, side="right") - 1
    frac = (u - bounds[m]) / (bounds[m + 1] - bounds[m])
    b = np.minimum((frac * BINS).astype(int), BINS - 1)
    rate = np.array([-(wb[b == i] @ rb[b == i]) / (rb[b == i] @ rb[b == i]) for i in range(BINS)])
    return rate / np.abs(rate).max()


def main(out):
    out = Path(out)
    rows = []
    base = None
    for path in sorted(out.glob("track_*.h5")):
        name = path.stem.removeprefix("track_")
        fr, a, supports, period = mid_span(path)
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
                local = where_fastest(out / f"run_{name}.h5", supports, period, wl)
                row["deepest"] = ("support", "quarter", "mid-span", "three quarters", "next support")[int(np.argmax(local))]
                row["local_rate"] = " ".join(f"{v:+.2f}" for v in local)
        rows.append(row)
        if name == "uniform":
            base = mean_peak
    for r in rows:
        r["ratio"] = r["mean_peak"] / base if base else float("nan")
    keys = ["case", "spans", "f_peak_hz", "mean_peak", "ratio", "largest_span_peak", "fastest_mm", "rate_db", "deepest", "local_rate"]
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
    print("| case | fastest-growing pattern | rate (dB per 1e5) | deepest | local rate across the span (support ... next support) |")
    print("|---|---|---|---|---|")
    for r in rows:
        if "fastest_mm" in r:
            print(f"| {r['case']} | {r['fastest_mm']:.1f} mm | {r['rate_db']:+.2f} | {r['deepest']} | {r['local_rate']} |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out/irregular_track")
