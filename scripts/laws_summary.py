"""The friction and wear laws study's table (scripts/laws_study.sh): per
variant, case (and rail) and speed, the fastest-growing harmonic, its
frequency and rate, and the rate's change from the base variant's at the
same harmonic where the base ran.

Usage: laws_summary.py OUT VARIANT [VARIANT ...]  (CSV on stdout; a
variant VARIANT=DIR reads its study from DIR instead of OUT/VARIANT)
"""

import csv
import sys
from pathlib import Path


def rows(folder: Path):
    """(case, label, speed m/s, wavelength m, frequency Hz, rate, growing)."""
    summary = folder / "mechanisms_summary.csv"
    if summary.exists():
        with summary.open() as f:
            for r in csv.DictReader(f):
                yield (r["mechanism"], r["label"], float(r["speed_m_s"]), float(r["peak_wavelength_m"]),
                       float(r["peak_frequency_hz"]), float(r["peak_rate_db_per_1e5"]), r["growing"])
    else:
        # A study stopped before its summary: each case's own speeds summary.
        for speeds in sorted(folder.glob("*/speeds_summary.csv")):
            case = speeds.parent.name
            if case.startswith("growth_"):
                continue
            with speeds.open() as f:
                for r in csv.DictReader(f):
                    label = r["label"] + (f" ({r['rail']})" if r.get("rail") else "")
                    yield (case, label, float(r["speed_m_s"]), float(r["peak_wavelength_m"]),
                           float(r["peak_frequency_hz"]), float(r["peak_rate_db_per_1e5"]), "")
    for config in ("growth_fastsim", "growth_exact"):
        speeds = folder / config / "speeds_summary.csv"
        if speeds.exists():
            with speeds.open() as f:
                for r in csv.DictReader(f):
                    yield (config, r["label"], float(r["speed_m_s"]), float(r["peak_wavelength_m"]),
                           float(r["peak_frequency_hz"]), float(r["peak_rate_db_per_1e5"]), "")


def main() -> None:
    out, variants = Path(sys.argv[1]), sys.argv[2:]
    folders = {v.split("=")[0]: Path(v.split("=")[1]) if "=" in v else out / v for v in variants}
    variants = list(folders)
    table = {v: list(rows(folders[v])) for v in variants}
    base = {(r[0], r[1]): r for r in table.get("base", [])}
    w = csv.writer(sys.stdout, lineterminator="\n")
    w.writerow(["variant", "case", "label", "speed_km_h", "peak_wavelength_mm", "peak_frequency_hz",
                "peak_rate_db_per_1e5", "base_peak_wavelength_mm", "base_peak_rate_db_per_1e5"])
    for v in variants:
        for case, label, speed, wl, fr, rate, _ in table[v]:
            b = base.get((case, label))
            w.writerow([v, case, label, f"{speed * 3.6:.0f}", f"{wl * 1e3:.1f}", f"{fr:.0f}", f"{rate:+.2f}",
                        f"{b[3] * 1e3:.1f}" if b else "", f"{b[5]:+.2f}" if b else ""])


if __name__ == "__main__":
    main()
