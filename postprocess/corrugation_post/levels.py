"""Figures in the field's units: the rail's roughness levels per band (dB re
1 µm, EN 15610) against the limit (ISO 3095 or the run's own curve), and when
each band reaches it.

* ``band_levels``: level against band centre wavelength, the wavelength
  decreasing along the axis as EN 15610 draws it, at chosen passages, with the
  limit curve (``levels.png``);
* ``level_growth``: level against traffic (MGT where the run gives axle loads,
  else wheel passages) for the bands nearest their limit, the crossing marked:
  a filled marker where a band reached its limit during the run, a hollow one
  where the last passage's rate takes it there (``level_growth.png``).

Passages are numbered from 1, as the terminal numbers them.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from .io import Run
from .units import values_in

LEVEL_VARS = ("roughness_level", "limit_level", "band")


def has_levels(run: Run) -> bool:
    """Whether the run file holds the band levels (written since issue 35)."""
    with run.pass_table() as ps:
        return all(v in ps.variables for v in LEVEL_VARS) and ps.sizes.get("band", 0) > 0


def _band_labels(band_mm: np.ndarray) -> list[str]:
    return [f"{w:.3g}" for w in band_mm]


def default_passes(count: int, n: int = 4) -> list[int]:
    """Up to ``n`` passage numbers (1-based) spread over ``count`` passages, the last included."""
    if count <= 0:
        return []
    picks = np.unique(np.linspace(1, count, min(n, count)).round().astype(int))
    return [int(p) for p in picks]


def band_levels(run: Run, out_dir: Path, at: list[int] | None = None) -> Path | None:
    """Band levels against wavelength at passages ``at`` (1-based; default:
    spread over the run), the levels before the first passage and the limit."""
    if not has_levels(run):
        return None
    with run.pass_table() as ps:
        band_mm = values_in(ps["band"], "mm")
        level = ps["roughness_level"].transpose("pass", "band").values
        limit = ps["limit_level"].values
        name = str(ps["limit_level"].attrs.get("limit_name", "limit"))
        initial = ps["initial_level"].values if "initial_level" in ps else None
        traffic = ps["traffic"].values if "traffic" in ps else np.arange(1, level.shape[0] + 1)
    count = level.shape[0]
    at = default_passes(count) if not at else at
    bad = [p for p in at if not 1 <= p <= count]
    if bad:
        raise ValueError(f"passage(s) {bad} not in the run (passages 1-{count})")
    fig = Figure(figsize=(9, 5), layout="constrained")
    ax = fig.add_subplot()
    x = np.arange(band_mm.size)  # band index: equal spacing per band, as EN 15610 draws it
    if initial is not None:
        ax.plot(x, initial, "o:", color="0.5", ms=4, label="before passage 1")
    for k, p in enumerate(at):
        ax.plot(x, level[p - 1], "o-", ms=4, color=f"C{k}", label=f"after passage {p} (traffic {traffic[p - 1]:.3g})")
    finite = np.isfinite(limit)
    if finite.any():
        ax.plot(x[finite], limit[finite], "k--", lw=2, label=f"{name} limit")
    ax.set_xticks(x, _band_labels(band_mm), rotation=60 if band_mm.size > 12 else 0)
    ax.set(xlabel="band centre wavelength (mm), decreasing", ylabel="roughness level (dB re 1 µm)",
           title=f"Rail roughness levels per one-third-octave band against the {name} limit\n"
                 f"contact model: {run.contact_model}")
    shown = level[[p - 1 for p in at]]
    floor = np.nanmin(shown[shown > -120]) if np.any(shown > -120) else -40.0
    ax.set_ylim(bottom=max(floor - 5.0, -60.0))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / "levels.png"
    fig.savefig(path, dpi=150)
    return path


def _traffic_axis(ps) -> tuple[np.ndarray, str, float | None]:
    """Traffic after each passage in the run's best unit, its label, and the
    factor from wheel passages to that unit (None where not constant)."""
    if "traffic_mgt" in ps and ps["traffic_mgt"].attrs.get("units") == "Mt":
        mgt = ps["traffic_mgt"].values
        passages = ps["traffic"].values
        return mgt, "traffic (MGT)", (mgt[-1] / passages[-1]) if passages[-1] > 0 else None
    return ps["traffic"].values, "traffic (wheel passages)", 1.0


def crossings(traffic: np.ndarray, initial: np.ndarray | None, level: np.ndarray,
              limit: np.ndarray) -> dict[int, float]:
    """Band index -> traffic at which its level first reached the limit during
    the run (linear between passages; from traffic 0 with the initial levels)."""
    t = np.r_[0.0, traffic] if initial is not None else traffic
    lv = np.vstack([initial, level]) if initial is not None else level
    out = {}
    for k in range(lv.shape[1]):
        if not np.isfinite(limit[k]):
            continue
        above = np.flatnonzero(lv[:, k] >= limit[k])
        above = above[above > 0]
        for i in above:
            if lv[i - 1, k] < limit[k]:
                f = (limit[k] - lv[i - 1, k]) / (lv[i, k] - lv[i - 1, k])
                out[k] = float(t[i - 1] + f * (t[i] - t[i - 1]))
                break
    return out


#: The level (dB re 1 µm) below which a band counts as absent from the
#: initial roughness (src/levels/forecast.rs, HELD_LEVEL).
HELD_LEVEL = -60.0


def level_growth(run: Run, out_dir: Path, bands: int = 6) -> Path | None:
    """Level against traffic for the ``bands`` bands nearest their limit (the
    band the run's last lines forecast first; bands absent from the initial
    roughness left out), the crossing marked (filled: during the run;
    hollow: forecast from the last passage's rate)."""
    if not has_levels(run):
        return None
    with run.pass_table() as ps:
        if ps.sizes.get("pass", 0) < 1:
            return None
        band_mm = values_in(ps["band"], "mm")
        level = ps["roughness_level"].transpose("pass", "band").values
        limit = ps["limit_level"].values
        name = str(ps["limit_level"].attrs.get("limit_name", "limit"))
        initial = ps["initial_level"].values if "initial_level" in ps else None
        to_limit = ps["passages_to_limit"].transpose("pass", "band").values if "passages_to_limit" in ps else None
        x, xlabel, per_passage = _traffic_axis(ps)
    finite = np.isfinite(limit)
    if not finite.any():
        return None
    # Bands absent from the initial roughness (below HELD_LEVEL before the
    # first passage) grow from nothing by the wear: no forecast, not drawn.
    held = initial > HELD_LEVEL if initial is not None else np.ones(limit.shape, bool)
    margin = np.where(finite & held, limit - np.nanmax(level, axis=0), np.inf)
    order = [int(k) for k in np.argsort(margin) if np.isfinite(margin[k])][:bands]
    # The band the run's last lines forecast comes first (as the terminal:
    # the fewest passages to the limit among the growing held bands).
    if to_limit is not None:
        last = np.where(held & finite & (to_limit[-1] > 0), to_limit[-1], np.inf)
        if np.isfinite(last).any():
            k = int(np.argmin(last))
            order = [k] + [o for o in order if o != k][: bands - 1]
    if not order:
        return None
    cross = crossings(x, initial, level, limit)
    t = np.r_[0.0, x] if initial is not None else x
    fig = Figure(figsize=(9, 5), layout="constrained")
    ax = fig.add_subplot()
    for c, k in enumerate(order):
        colour = f"C{c}"
        lv = np.r_[initial[k], level[:, k]] if initial is not None else level[:, k]
        ax.plot(t, lv, "-", color=colour, label=f"{band_mm[k]:.3g} mm (limit {limit[k]:.1f} dB)")
        ax.axhline(limit[k], color=colour, ls=":", lw=1)
        if k in cross:
            ax.plot(cross[k], limit[k], "o", color=colour, ms=8)
        elif to_limit is not None and per_passage is not None and np.isfinite(to_limit[-1, k]) \
                and to_limit[-1, k] > 0 and x[-1] + to_limit[-1, k] * per_passage <= 3 * max(x[-1], 1e-30):
            end = x[-1] + to_limit[-1, k] * per_passage
            ax.plot([x[-1], end], [level[-1, k], limit[k]], "--", color=colour, lw=1)
            ax.plot(end, limit[k], "o", mfc="none", color=colour, ms=8)
    # The levels near the limits: a band rising from far below would squash them.
    shown_limits = limit[order]
    top = max(float(np.max(shown_limits)), float(np.max(level[:, order]))) + 3.0
    ax.set_ylim(max(float(np.min(shown_limits)) - 25.0, float(np.min(level[:, order])) - 3.0), top)
    ax.set(xlabel=xlabel, ylabel="roughness level (dB re 1 µm)",
           title=f"Band levels against traffic, {name} limit dotted\n"
                 "● reached during the run, ○ forecast at the last passage's rate (within 3x the simulated traffic)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, title="band", title_fontsize=8)
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / "level_growth.png"
    fig.savefig(path, dpi=150)
    return path
