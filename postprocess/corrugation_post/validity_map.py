"""Validity map of a normal contact on a corrugated rail against the
nonlinear profile contact (``scripts/validity_map.sh``): the Hertz contact
(``"hertz"``) or the linear profile contact (``"linear"``).

Input: a manifest CSV with columns ``wavelength, amplitude, normal, file,
exit_code, message, contact_loss``: one growth passage per harmonic
corrugation (wavelength m, amplitude m) with ``contact.normal`` the
candidate and with ``"profile"``. Per corrugation:

- ``mean_difference``: relative difference of the mean wear depth of the
  passage, ``|w_h - w_p| / |w_p|``;
- ``harmonic_difference``: relative difference of the complex first
  harmonic (the corrugation's wavelength) of the centre-line wear the
  corrugation drives, ``|W_h - W_p| / |W_p|`` with ``W = W(A) - W(0)``
  (each model's wear less its wear on a smooth rail, the amplitude-0 row:
  what the two runs' grids discretise alike, the run-in transient included,
  cancels), which holds both amplitude and phase;
- ``amplitude_ratio`` ``|W_h| / |W_p|`` and ``phase_difference`` (degrees);
- ``outcome``: ``both`` when both runs finished, else what failed.

Writes ``validity.csv`` (the columns of :data:`COLUMNS`), ``validity.md``
and ``validity_map.png``: both differences over (wavelength, amplitude) with
the 5 % line, failed runs marked.
"""

from __future__ import annotations

import math
from collections import defaultdict
from pathlib import Path

import numpy as np

from .io import Run, read_csv, write_csv

COLUMNS = ("wavelength", "amplitude", "mean_difference", "harmonic_difference", "amplitude_ratio",
           "phase_difference", "contact_loss", "outcome")

# The line where the Hertz contact stops being good enough.
THRESHOLD = 0.05
# Below this amplitude the profile contact's own wear harmonic is within a
# factor of two of its noise floor at 0.4 mm elements (docs/src/theory/validity-maps.md).
PROFILE_USABLE = 5e-6


def _wear(path, wavelength):
    """(mean wear depth, complex first harmonic of the centre-line wear) of a run's first passage."""
    run = Run.open(path)
    with run.rail() as rail:
        wear = rail["wear"].isel({"pass": 0})
        x = rail["x"].values
        centre = wear.sel(y=0.0, method="nearest").values
        mean = float(wear.values.mean())
    k = 2.0 * math.pi / wavelength
    harmonic = 2.0 / len(x) * np.sum(centre * np.exp(-1j * k * x))
    return mean, harmonic


def candidate(rows) -> str:
    """The normal contact compared with ``"profile"`` in a manifest."""
    names = sorted({r["normal"] for r in rows} - {"profile"})
    if len(names) != 1:
        raise ValueError(f"a validity manifest compares one normal contact with 'profile', found {names}")
    return names[0]


def evaluate(rows):
    name = candidate(rows)
    cases = defaultdict(dict)
    for r in rows:
        cases[(float(r["wavelength"]), float(r["amplitude"]))][r["normal"]] = r
    smooth = {}
    for (wavelength, amplitude), pair in cases.items():
        if amplitude == 0.0:
            for n, r in pair.items():
                if int(r["exit_code"]) == 0:
                    smooth[(wavelength, n)] = _wear(r["file"], wavelength)[1]
    out = []
    for (wavelength, amplitude), pair in sorted(cases.items()):
        if amplitude == 0.0:
            continue
        row = dict(wavelength=wavelength, amplitude=amplitude, mean_difference=math.nan,
                   harmonic_difference=math.nan, amplitude_ratio=math.nan, phase_difference=math.nan)
        row["contact_loss"] = sum(int(r.get("contact_loss") or 0) for r in pair.values())
        failed = [n for n in (name, "profile") if n not in pair or int(pair[n]["exit_code"]) != 0]
        if failed:
            messages = "; ".join(pair[n]["message"] for n in failed if n in pair)
            row["outcome"] = f"{' and '.join(failed)} failed: {messages}".strip()
        else:
            mh, wh = _wear(pair[name]["file"], wavelength)
            mp, wp = _wear(pair["profile"]["file"], wavelength)
            wh -= smooth.get((wavelength, name), 0.0)
            wp -= smooth.get((wavelength, "profile"), 0.0)
            row.update(mean_difference=abs(mh - mp) / abs(mp), harmonic_difference=abs(wh - wp) / abs(wp),
                       amplitude_ratio=abs(wh) / abs(wp),
                       phase_difference=math.degrees(np.angle(wh / wp)), outcome="both")
        out.append(row)
    return out


def chart(rows, path, name="hertz"):
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm

    lams = sorted({r["wavelength"] for r in rows})
    amps = sorted({r["amplitude"] for r in rows})
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
    for ax, key, title in ((axes[0], "mean_difference", "mean wear per passage"),
                           (axes[1], "harmonic_difference", "first harmonic of the wear")):
        z = np.full((len(amps), len(lams)), np.nan)
        for r in rows:
            z[amps.index(r["amplitude"]), lams.index(r["wavelength"])] = 100.0 * r[key]
        x = np.array(lams) * 1e3
        y = np.array(amps) * 1e6
        mesh = ax.pcolormesh(x, y, np.clip(z, 0.1, 1000.0), shading="nearest", cmap="viridis",
                             norm=LogNorm(0.1, 1000.0))
        if np.isfinite(z).sum() >= 4:
            filled = np.where(np.isfinite(z), z, 1000.0)
            cs = ax.contour(x, y, filled, levels=[100.0 * THRESHOLD], colors="w", linewidths=2)
            ax.clabel(cs, fmt="5 %%")
        for r in rows:
            if r["outcome"] != "both":
                ax.plot(r["wavelength"] * 1e3, r["amplitude"] * 1e6, "rx", ms=9)
            elif r["contact_loss"]:
                ax.plot(r["wavelength"] * 1e3, r["amplitude"] * 1e6, "o", mfc="none", mec="orange", ms=9)
        ax.axhline(PROFILE_USABLE * 1e6, color="w", ls="--", lw=1)
        ax.text(x[0], PROFILE_USABLE * 1e6 * 0.85, " profile contact's noise floor x 2 (0.4 mm grid)", color="w",
                fontsize=8, va="top")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("corrugation wavelength (mm)")
        ax.set_title(f"{name} vs profile: {title} (%)")
        fig.colorbar(mesh, ax=ax)
    axes[0].set_ylabel("corrugation amplitude (um)")
    fig.suptitle(f"Validity of the {name} normal contact (x: run failed, full sliding; o: contact loss)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def markdown(rows) -> str:
    lines = ["| wavelength mm | amplitude um | mean wear | first harmonic | amplitude ratio | phase deg | outcome |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        def pct(v):
            return "-" if math.isnan(v) else f"{100 * v:.1f} %"
        phase = "-" if math.isnan(r["phase_difference"]) else f"{r['phase_difference']:.1f}"
        ratio = "-" if math.isnan(r["amplitude_ratio"]) else f"{r['amplitude_ratio']:.3f}"
        outcome = r["outcome"] + (" (contact loss)" if r["contact_loss"] and r["outcome"] == "both" else "")
        lines.append(f"| {1e3 * r['wavelength']:.0f} | {1e6 * r['amplitude']:.0f} | {pct(r['mean_difference'])} | "
                     f"{pct(r['harmonic_difference'])} | {ratio} | {phase} | {outcome} |")
    return "\n".join(lines)


def run(manifest, out):
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    manifest_rows = read_csv(manifest)
    rows = evaluate(manifest_rows)
    paths = [write_csv(out / "validity.csv", COLUMNS, rows)]
    (out / "validity.md").write_text(markdown(rows) + "\n")
    paths.append(out / "validity.md")
    chart(rows, out / "validity_map.png", candidate(manifest_rows))
    paths.append(out / "validity_map.png")
    return rows, paths
