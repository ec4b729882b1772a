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


# Each rail's marker and line (the first rail's are those of a one-rail file).
RAIL_STYLES = (("o", "-"), ("s", "--"))
# The passages' colours (C7, grey, is the levels before the first passage's).
PALETTE = (0, 1, 2, 3, 4, 5, 6, 8, 9)


def _read_levels(run: Run) -> dict:
    """One rail's band levels, limit and traffic."""
    with run.pass_table() as ps:
        level = ps["roughness_level"].transpose("pass", "band").values
        return {
            "band_mm": values_in(ps["band"], "mm"), "level": level, "limit": ps["limit_level"].values,
            "name": str(ps["limit_level"].attrs.get("limit_name", "limit")),
            "initial": ps["initial_level"].values if "initial_level" in ps else None,
            "traffic": ps["traffic"].values if "traffic" in ps else np.arange(1, level.shape[0] + 1),
        }


def _rail_levels(ax, d: dict, at: list[int], style: tuple[str, str], rail: str, first_colour: int = 0) -> None:
    """One rail's levels before the first passage and after passages ``at``,
    in the colours from ``C{first_colour}`` on (each rail its own)."""
    x = np.arange(d["band_mm"].size)
    marker, line = style
    named = f"{rail}, " if rail else ""
    if d["initial"] is not None:
        ax.plot(x, d["initial"], f"{marker}:", color="0.5", ms=4, label=f"{named}before passage 1")
    for k, p in enumerate(at):
        ax.plot(x, d["level"][p - 1], f"{marker}{line}", ms=4, color=f"C{PALETTE[(first_colour + k) % len(PALETTE)]}",
                label=f"{named}after passage {p} (traffic {d['traffic'][p - 1]:.3g})")


def _limit_lines(ax, found) -> None:
    """The limit curve, once where the rails share it."""
    drawn = []
    for r, d in found:
        limit, finite = d["limit"], np.isfinite(d["limit"])
        if not finite.any() or any(np.array_equal(limit, o, equal_nan=True) for o in drawn):
            continue
        named = f" ({r.rail_name})" if drawn else ""
        ax.plot(np.arange(limit.size)[finite], limit[finite], "k--" if not drawn else "k-.", lw=2,
                label=f"{d['name']} limit{named}")
        drawn.append(limit)


def band_levels(run: Run, out_dir: Path, at: list[int] | None = None) -> Path | None:
    """Band levels against wavelength at passages ``at`` (1-based; default:
    spread over the run), the levels before the first passage and the limit;
    every rail's on the same axes (marker and line per rail)."""
    if not has_levels(run):
        return None
    found = [(r, _read_levels(r)) for r in run.rails() if has_levels(r)]
    first = found[0][1]
    band_mm, count = first["band_mm"], first["level"].shape[0]
    at = default_passes(count) if not at else at
    bad = [p for p in at if not 1 <= p <= count]
    if bad:
        raise ValueError(f"passage(s) {bad} not in the run (passages 1-{count})")
    fig = Figure(figsize=(9, 5 + 0.5 * (len(found) - 1)), layout="constrained")
    ax = fig.add_subplot()
    x = np.arange(band_mm.size)  # band index: equal spacing per band, as EN 15610 draws it
    for i, ((r, d), style) in enumerate(zip(found, RAIL_STYLES)):
        _rail_levels(ax, d, at, style, r.rail_name, first_colour=i * len(at))
    _limit_lines(ax, found)
    ax.set_xticks(x, _band_labels(band_mm), rotation=60 if band_mm.size > 12 else 0)
    ax.set(xlabel="band centre wavelength (mm), decreasing", ylabel="roughness level (dB re 1 µm)",
           title=f"Rail roughness levels per one-third-octave band against the {first['name']} limit\n"
                 f"contact model: {run.contact_model}")
    shown = np.concatenate([d["level"][[p - 1 for p in at]] for _, d in found])
    floor = np.nanmin(shown[shown > -120]) if np.any(shown > -120) else -40.0
    ax.set_ylim(bottom=max(floor - 5.0, -60.0))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, ncols=2 if len(found) > 1 else 1)
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


def _read_growth(run: Run) -> dict | None:
    """One rail's levels against traffic and its forecast; None without passages."""
    with run.pass_table() as ps:
        if ps.sizes.get("pass", 0) < 1:
            return None
        x, xlabel, per_passage = _traffic_axis(ps)
        return {
            "band_mm": values_in(ps["band"], "mm"),
            "level": ps["roughness_level"].transpose("pass", "band").values,
            "limit": ps["limit_level"].values, "name": str(ps["limit_level"].attrs.get("limit_name", "limit")),
            "initial": ps["initial_level"].values if "initial_level" in ps else None,
            "to_limit": ps["passages_to_limit"].transpose("pass", "band").values if "passages_to_limit" in ps else None,
            "x": x, "xlabel": xlabel, "per_passage": per_passage,
        }


def _nearest_bands(d: dict, bands: int) -> list[int]:
    """The ``bands`` bands nearest their limit, the band the run's last lines
    forecast first coming first (as the terminal: the fewest passages to the
    limit among the growing held bands).  Bands absent from the initial
    roughness (below HELD_LEVEL before the first passage) grow from nothing
    by the wear: no forecast, not drawn."""
    limit, initial, to_limit = d["limit"], d["initial"], d["to_limit"]
    finite = np.isfinite(limit)
    if not finite.any():
        return []
    held = initial > HELD_LEVEL if initial is not None else np.ones(limit.shape, bool)
    margin = np.where(finite & held, limit - np.nanmax(d["level"], axis=0), np.inf)
    nearest = [int(k) for k in np.argsort(margin) if np.isfinite(margin[k])]
    # Half the bands the ones that rose most over the run (the growing
    # ones, which the nearest decaying bands would crowd out), the rest the
    # nearest their limit.
    start = initial if initial is not None else d["level"][0]
    rise = np.where(finite & held, d["level"][-1] - start, -np.inf)
    rising = [int(k) for k in np.argsort(-rise) if rise[k] > 0][: bands // 2]
    order = list(dict.fromkeys(rising + nearest))[:bands]
    if to_limit is not None:
        last = np.where(held & finite & (to_limit[-1] > 0), to_limit[-1], np.inf)
        if np.isfinite(last).any():
            k = int(np.argmin(last))
            order = [k] + [o for o in order if o != k][: bands - 1]
    return order


def _draw_level_growth(ax, d: dict, order: list[int], colours: dict[int, str]) -> tuple[float, float, set]:
    """One rail's band levels against traffic, limits dotted, crossings
    marked; returns the level range to show and the markers drawn
    ("reached", "forecast")."""
    drawn = set()
    x, level, limit, initial, to_limit = d["x"], d["level"], d["limit"], d["initial"], d["to_limit"]
    cross = crossings(x, initial, level, limit)
    t = np.r_[0.0, x] if initial is not None else x
    for k in order:
        colour = colours[k]
        lv = np.r_[initial[k], level[:, k]] if initial is not None else level[:, k]
        ax.plot(t, lv, "-", color=colour, label=f"{d['band_mm'][k]:.3g} mm (limit {limit[k]:.1f} dB)")
        ax.axhline(limit[k], color=colour, ls=":", lw=1)
        if k in cross:
            ax.plot(cross[k], limit[k], "o", color=colour, ms=8)
            drawn.add("reached")
        elif to_limit is not None and d["per_passage"] is not None and np.isfinite(to_limit[-1, k]) \
                and to_limit[-1, k] > 0 and x[-1] + to_limit[-1, k] * d["per_passage"] <= 3 * max(x[-1], 1e-30):
            end = x[-1] + to_limit[-1, k] * d["per_passage"]
            ax.plot([x[-1], end], [level[-1, k], limit[k]], "--", color=colour, lw=1)
            ax.plot(end, limit[k], "o", mfc="none", color=colour, ms=8)
            drawn.add("forecast")
    # The levels near the limits: a band rising from far below would squash them.
    shown_limits = limit[order]
    top = max(float(np.max(shown_limits)), float(np.max(level[:, order]))) + 3.0
    return max(float(np.min(shown_limits)) - 25.0, float(np.min(level[:, order])) - 3.0), top, drawn


def level_growth(run: Run, out_dir: Path, bands: int = 6) -> Path | None:
    """Level against traffic for ``bands`` bands: the band the run's last
    lines forecast first, the half that rose most over the run, the rest
    the nearest their limit (bands absent from the initial roughness left
    out), the crossing marked (filled: during the run;
    hollow: forecast from the last passage's rate).  Two rails: a panel per
    rail, side by side on the same level axis, a band the same colour in both."""
    if not has_levels(run):
        return None
    found = [(r, d) for r in run.rails() if has_levels(r) and (d := _read_growth(r)) is not None]
    found = [(r, d, order) for r, d in found if (order := _nearest_bands(d, bands))]
    if not found:
        return None
    union = list(dict.fromkeys(k for _, _, order in found for k in order))
    colours = {k: f"C{c % 10}" for c, k in enumerate(union)}
    fig = Figure(figsize=(9 if len(found) == 1 else 15, 5), layout="constrained")
    axes = [fig.add_subplot()] if len(found) == 1 else list(fig.subplots(1, len(found), sharex=True, sharey=True))
    ranges = [_draw_level_growth(ax, d, order, colours) for ax, (_, d, order) in zip(axes, found)]
    axes[0].set_ylim(min(r[0] for r in ranges), max(r[1] for r in ranges))
    drawn = set().union(*(r[2] for r in ranges))
    words = {"reached": "● reached during the run",
             "forecast": "○ forecast at the last passage's rate (within 3x the simulated traffic)"}
    marks = ", ".join(words[m] for m in ("reached", "forecast") if m in drawn) or \
        "no band reached the limit, or reaches it within 3x the simulated traffic"
    title = f"Band levels against traffic, {found[0][1]['name']} limit dotted\n{marks}"
    for ax, (r, d, _) in zip(axes, found):
        ax.set(xlabel=d["xlabel"], ylabel="roughness level (dB re 1 µm)", title=r.rail_name or title)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, title="band", title_fontsize=8)
    if len(found) > 1:
        fig.suptitle(title)
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / "level_growth.png"
    fig.savefig(path, dpi=150)
    return path
