"""Figures of one run: wear maps (paper Figs. 6-8), loads, traction snapshots
(Figs. 3-4), growth, and the roughness levels against their limit
(``levels.py``).

Every figure function takes a ``Run``, a stored passage index (the ``pass``
coordinate, from 0) and an output folder, writes one PNG and returns its
path.  Titles number passages from 1, as the terminal does; lengths are in
mm, roughness in µm or dB re 1 µm.  Figures are built on
``matplotlib.figure.Figure`` objects (no pyplot, no display needed).
"""

from __future__ import annotations

from pathlib import Path
from typing import Callable

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator
from matplotlib.tri import Triangulation

from .io import Run, RunFileError
from .schema import FIELDS
from .units import depth_unit, values_in

DPI = 150


def _title(run: Run, what: str, pass_index: int, note: str = "") -> str:
    return f"{what}, passage {pass_index + 1}{note}\ncontact model: {run.contact_model}"


def _save(fig: Figure, out_dir: Path, name: str) -> Path:
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / name
    fig.savefig(path, dpi=DPI)
    return path


def _traffic_note(rail, pass_index: int) -> str:
    """Where the passage stands in the study: the traffic the rail has seen
    up to it (the passage's own wear is one simulated wheel passage's)."""
    if "traffic" not in rail:
        return ""
    seen = float(rail["traffic"].sel({"pass": pass_index}).values)
    return f" (the rail has seen {seen:.3g} wheel passages in all)"


def _wear_title(run: Run, pass_index: int, note: str) -> str:
    # One line per statement: the figure is 9 inches wide.
    seen = f"\n{note.strip(' ()')}" if note else ""
    return (f"Wear depth of passage {pass_index + 1} alone: one wheel passage, unscaled{seen}\n"
            f"contact model: {run.contact_model}")


def wear_map(run: Run, pass_index: int, out_dir: Path) -> Path:
    """Wear depth of one passage over the rail stretch, colour in nm or µm (by its size)."""
    with run.rail() as rail:
        wear = rail["wear"].sel({"pass": pass_index}).transpose("y", "x").load()
        x, y = values_in(rail["x"], "mm"), values_in(rail["y"], "mm")
        note = _traffic_note(rail, pass_index)
    fig = Figure(figsize=(9, 4), layout="constrained")
    ax = fig.add_subplot()
    unit, label = depth_unit(wear)
    mesh = ax.pcolormesh(x, y, values_in(wear, unit), shading="auto", cmap="viridis")
    fig.colorbar(mesh, ax=ax, label=f"wear depth ({label})")
    ax.set(xlabel="x along rail (mm)", ylabel="y lateral (mm)",
           title=_wear_title(run, pass_index, note))
    return _save(fig, out_dir, "wear_map.png")


def wear_centreline(run: Run, pass_index: int, out_dir: Path) -> Path:
    """Wear depth along the grid row nearest y = 0, and its lateral maximum, vs x."""
    with run.rail() as rail:
        wear = rail["wear"].sel({"pass": pass_index}).load()
        x = values_in(rail["x"], "mm")
        row = wear.sel(y=0.0, method="nearest")
        y0 = float(values_in(row["y"], "mm"))
        note = _traffic_note(rail, pass_index)
    fig = Figure(figsize=(9, 4), layout="constrained")
    ax = fig.add_subplot()
    unit, label = depth_unit(wear)
    ax.plot(x, values_in(row, unit), label=f"centre line (y = {y0:.2f} mm)")
    ax.plot(x, values_in(wear.max("y"), unit), "--", label="maximum over y")
    ax.set(xlabel="x along rail (mm)", ylabel=f"wear depth ({label})",
           title=_wear_title(run, pass_index, note))
    ax.grid(alpha=0.3)
    ax.legend()
    return _save(fig, out_dir, "wear_centreline.png")


def contact_mask(ct) -> np.ndarray:
    """Boolean mask of steps with the wheel in contact."""
    if "in_contact" in ct:
        return np.asarray(ct["in_contact"].values) != 0
    return (np.asarray(ct["normal_force"].values) > 0) & (np.asarray(ct["max_pressure"].values) > 0)


def _shade_loss_of_contact(ax, xc: np.ndarray, contact: np.ndarray) -> None:
    """Grey spans where the wheel is out of contact."""
    if contact.all():
        return
    edges = np.flatnonzero(np.diff(np.r_[0, (~contact).astype(int), 0]))
    for start, stop in zip(edges[::2], edges[1::2]):
        ax.axvspan(xc[start], xc[stop - 1], color="0.85", lw=0)


def _creepage_sign_note(cx: np.ndarray) -> str:
    if np.all(cx <= 0):
        return "creepage_x ≤ 0 at every step (|·| plotted)"
    if np.all(cx >= 0):
        return "creepage_x ≥ 0 at every step (|·| plotted)"
    return f"creepage_x changes sign: > 0 at {np.count_nonzero(cx > 0)} of {cx.size} steps (▲)"


def loads(run: Run, pass_index: int, out_dir: Path) -> Path:
    """Stacked panels vs patch centre: forces, |creepage_x|, semi-axes (+ optional extras)."""
    with run.contact(pass_index) as ct:
        ct = ct.load()
    xc = values_in(ct["x_c"], "mm")
    contact = contact_mask(ct)
    # The iterations where the model iterates (FASTSIM records zeros).
    extra = [v for v in ("newton_iterations",) if v in ct and np.any(ct[v].values != 0)]
    fig = Figure(figsize=(8, 2.0 * (4 + len(extra)) + 0.8), layout="constrained")
    axes = fig.subplots(4 + len(extra), 1, sharex=True)
    axes[0].plot(xc, values_in(ct["normal_force"], "kN"))
    axes[0].set_ylabel("normal force (kN)")
    axes[1].plot(xc, values_in(ct["longitudinal_force"], "kN"))
    axes[1].set_ylabel("longitudinal\nforce (kN)")
    cx = values_in(ct["creepage_x"], "1")
    axes[2].plot(xc, np.abs(cx), label=_creepage_sign_note(cx))
    if np.any(cx > 0) and np.any(cx < 0):
        axes[2].plot(xc[cx > 0], np.abs(cx[cx > 0]), "^", ms=3, color="C3")
    axes[2].set_ylabel("|creepage_x|")
    axes[2].legend(fontsize=8)
    axes[3].plot(xc, values_in(ct["semi_axis_a"], "mm"), label="a (along rail)")
    axes[3].plot(xc, values_in(ct["semi_axis_b"], "mm"), label="b (lateral)")
    axes[3].set_ylabel("semi-axes (mm)")
    axes[3].legend(fontsize=8)
    for ax, name in zip(axes[4:], extra):
        ax.plot(xc, ct[name].values, drawstyle="steps-mid")
        ax.set_ylabel("iterations\nper step")
    for ax in axes:
        _shade_loss_of_contact(ax, xc, contact)
        ax.grid(alpha=0.3)
        # A constant force prescribed to round-off must not plot as noise
        # around an offset.
        ax.ticklabel_format(axis="y", useOffset=False, style="plain")
        lo, hi = ax.get_ylim()
        if hi - lo < 1e-6 * max(abs(lo), abs(hi), 1e-30):
            mid = 0.5 * (lo + hi)
            ax.set_ylim(mid - 0.05 * abs(mid) - 1e-12, mid + 0.05 * abs(mid) + 1e-12)
    axes[-1].set_xlabel("patch centre x_c (mm)")
    fig.suptitle(_title(run, "Contact loads", pass_index))
    return _save(fig, out_dir, "loads.png")


def snapshot_steps(xc: np.ndarray, contact: np.ndarray, count: int = 4) -> np.ndarray:
    """Indices of ``count`` in-contact steps evenly spread over the recorded x_c range.

    The targets are the centres of ``count`` equal intervals, so the first and
    last steps (often start-up transients) are avoided.
    """
    candidates = np.flatnonzero(contact)
    if candidates.size == 0:
        raise RunFileError("no step with the wheel in contact")
    lo, hi = xc[candidates].min(), xc[candidates].max()
    targets = lo + (np.arange(count) + 0.5) / count * (hi - lo)
    return np.array([candidates[np.argmin(np.abs(xc[candidates] - t))] for t in targets])


def _patch_panel(ax, xi, eta, value, stick, levels, cmap):
    """One normalised-patch panel; falls back to a scatter when the mesh is one strip."""
    try:
        tri = Triangulation(xi, eta)
        art = ax.tricontourf(tri, value, levels=levels, cmap=cmap, extend="both")
        if stick is not None and 0 < stick.mean() < 1:
            ax.tricontour(tri, stick.astype(float), levels=[0.5], colors="k", linewidths=1)
    except (ValueError, RuntimeError):
        art = ax.scatter(xi, eta, c=value, cmap=cmap, vmin=levels[0], vmax=levels[-1], s=12)
    t = np.linspace(0, 2 * np.pi, 200)
    ax.plot(np.cos(t), np.sin(t), "k-", lw=0.6)
    ax.set_aspect("equal")
    # The adapted mesh fills the unit circle; a fixed grid reaches beyond it.
    lim = max(1.05, float(np.max(np.abs(xi))), float(np.max(np.abs(eta))))
    ax.set(xlim=(-lim, lim), ylim=(-lim, lim), xlabel="ξ = x/a  (leading edge →)")
    return art


def traction_snapshots(run: Run, pass_index: int, out_dir: Path, count: int = 4) -> Path:
    """traction_x / (mu p0) over the normalised patch at ``count`` steps, plus their position."""
    mu = run.friction_coefficient
    with run.contact(pass_index) as ct:
        ct = ct.load()
    xc = values_in(ct["x_c"], "mm")
    contact = contact_mask(ct)
    steps = snapshot_steps(xc, contact, count)
    xi, eta = ct["xi"].values, ct["eta"].values
    p0 = values_in(ct["max_pressure"], "Pa")[steps]
    if not any(v in ct for v in FIELDS):
        raise FigureSkipped("the run stored no contact fields (output.store_fields = false): "
                            "traction_snapshots.png skipped")
    qx = values_in(ct["traction_x"], "Pa")[steps]
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = qx / (mu * p0[:, None])
    lim = float(np.nanmax(np.abs(ratio))) if np.isfinite(ratio).any() else 0.0
    levels = MaxNLocator(nbins=20, symmetric=True).tick_values(-lim, lim) if lim > 0 else np.linspace(-1, 1, 21)
    stick = ct["stick"].values[steps] if "stick" in ct else [None] * count

    fig = Figure(figsize=(3.2 * count, 6), layout="constrained")
    grid = fig.add_gridspec(2, count, height_ratios=(1, 2.2))
    top = fig.add_subplot(grid[0, :])
    top.plot(xc, values_in(ct["normal_force"], "kN"), color="0.3")
    top.set(xlabel="patch centre x_c (mm)", ylabel="normal force (kN)")
    top.grid(alpha=0.3)
    art = None
    for k, s in enumerate(steps):
        top.axvline(xc[s], color="C3", lw=1)
        top.annotate(str(k + 1), (xc[s], 1.0), xycoords=("data", "axes fraction"),
                     ha="center", va="bottom", color="C3")
        ax = fig.add_subplot(grid[1, k])
        art = _patch_panel(ax, xi, eta, ratio[k], stick[k], levels, "RdBu_r")
        t_ms = float(values_in(ct["time"], "ms")[s])
        ax.set_title(f"{k + 1}: x_c = {xc[s]:.1f} mm\nt = {t_ms:.3f} ms", fontsize=9)
        if k == 0:
            ax.set_ylabel("η = y/b")
    fig.colorbar(art, ax=fig.axes[1:], label=f"traction_x / (μ p0),  μ = {mu:g}", shrink=0.8)
    fig.suptitle(_title(run, "Longitudinal traction (black: stick/slip boundary)", pass_index))
    return _save(fig, out_dir, "traction_snapshots.png")


# ---------------------------------------------------------------- optional figures

def _find_spectrum(run: Run, names=("spectrum",)):
    """The first ``<name>(pass, <wavelength>)`` variable, trying ``names`` in
    order, in ``passes`` or ``rail``."""
    for name in names:
        for opener in (run.pass_table, run.rail):
            with opener() as ds:
                spec = ds.get(name)
                if spec is not None and spec.ndim == 2 and "pass" in spec.dims:
                    return spec.load()
    return None


def spectrum(run: Run, pass_index: int, out_dir: Path) -> Path | None:
    """spectrum(pass, wavelength) of the chosen passage, if the run file has one."""
    spec = _find_spectrum(run)
    if spec is None or pass_index not in spec["pass"].values:
        return None
    spec = spec.sel({"pass": pass_index})
    wl = spec[spec.dims[0]]
    fig = Figure(figsize=(8, 4), layout="constrained")
    ax = fig.add_subplot()
    # Amplitudes in µm, wavelengths in mm (the units of the other figures);
    # a spectrum in other units (a PSD) is drawn as stored.
    try:
        y, ylabel = values_in(spec, "um"), "amplitude (µm)"
    except ValueError:
        y, ylabel = spec.values, f"{spec.attrs.get('long_name', 'spectrum')} ({spec.attrs.get('units', '?')})"
    try:
        ax.semilogx(values_in(wl, "mm"), y, "o-", ms=2)
        ax.set_xlabel(f"{wl.name} (mm)")
    except ValueError:
        ax.semilogx(wl.values, y, "o-", ms=2)
        ax.set_xlabel(f"{wl.name} ({wl.attrs.get('units', '?')})")
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3, which="both")
    ax.set_title(_title(run, "Centre-line corrugation amplitude spectrum", pass_index))
    return _save(fig, out_dir, "spectrum.png")


def rms_growth(run: Run, pass_index: int, out_dir: Path) -> Path | None:
    """RMS corrugation vs traffic, when more than one passage is recorded; with
    the traffic scale m and the update ratio (its stability criterion) below
    when the run file has them."""
    with run.pass_table() as ps:
        if "rms_corrugation" not in ps or ps.sizes.get("pass", 0) < 2:
            return None
        traffic = ps["traffic"].values if "traffic" in ps else ps["pass"].values
        rms = values_in(ps["rms_corrugation"], "um")
        scaling = "traffic_scale" in ps and "update_ratio" in ps
        if scaling:
            scale, ratio = ps["traffic_scale"].values, ps["update_ratio"].values
    fig = Figure(figsize=(8, 6 if scaling else 4), layout="constrained")
    axes = fig.subplots(2 if scaling else 1, 1, squeeze=False, sharex=True)[:, 0]
    axes[0].plot(traffic, rms, "o-", ms=3)
    axes[0].set(ylabel="rms corrugation (µm)", title=f"{_rms_trend(rms, traffic)}\ncontact model: {run.contact_model}")
    axes[0].grid(alpha=0.3)
    if scaling:
        axes[1].semilogy(traffic, scale, "o-", ms=3, label="traffic scale m (passages per update)")
        axes[1].set_ylabel("m")
        twin = axes[1].twinx()
        twin.plot(traffic, ratio, "s-", ms=2, color="tab:red", label="update ratio q")
        twin.set_ylabel("update ratio q = m max|W_k|/|R_k|", color="tab:red")
        axes[1].grid(alpha=0.3)
    axes[-1].set_xlabel("traffic (passages)")
    return _save(fig, out_dir, "rms_corrugation.png")


def _rms_trend(rms_um: np.ndarray, traffic: np.ndarray) -> str:
    """What the rms does over the run, in words: grows, falls or holds."""
    first, last = float(rms_um[0]), float(rms_um[-1])
    if first > 0 and abs(last / first - 1) < 0.01:
        verb = "holds at"
        return f"The rms corrugation {verb} {last:.3g} µm over {traffic[-1]:.3g} wheel passages"
    verb = "grows" if last > first else "falls"
    return f"The rms corrugation {verb} from {first:.3g} to {last:.3g} µm over {traffic[-1]:.3g} wheel passages"


def profile_snapshots(run: Run, pass_index: int, out_dir: Path) -> Path | None:
    """Centre-line rail profile (minus its mean) at up to six stored passages,
    coloured by traffic (growth studies)."""
    with run.rail() as rail:
        if "profile" not in rail or rail.sizes.get("pass", 0) < 2:
            return None
        line = rail["profile"].sel(y=0.0, method="nearest").load()
        traffic = rail["traffic"].values if "traffic" in rail else rail["pass"].values
        passes = rail["pass"].values
        x_mm = values_in(rail["x"], "mm")
    picks = np.unique(np.linspace(0, line.sizes["pass"] - 1, min(6, line.sizes["pass"])).round().astype(int))
    um = values_in(line, "um")
    fig = Figure(figsize=(9, 4), layout="constrained")
    ax = fig.add_subplot()
    colours = [f"C{k}" for k in range(len(picks))]
    for colour, k in zip(colours, picks):
        ax.plot(x_mm, um[k] - um[k].mean(), color=colour, lw=1.2,
                label=f"after passage {passes[k] + 1} (traffic {traffic[k]:.3g})")
    ax.set(xlabel="x (mm)", ylabel="profile minus mean (µm)",
           title=f"Rail profile on the centre line at stored passages\ncontact model: {run.contact_model}")
    ax.legend(fontsize=8, ncols=2)
    ax.grid(alpha=0.3)
    return _save(fig, out_dir, "profile_snapshots.png")


def spectrogram(run: Run, pass_index: int, out_dir: Path) -> Path | None:
    """Corrugation amplitude against wavelength and traffic (growth studies),
    with the growth rate per wavelength averaged over the run when present.
    Uses the contact-filtered spectrum (what the wheel sees, on which the
    growth rates are computed) when the file has it."""
    spec = _find_spectrum(run, ("filtered_spectrum", "spectrum"))
    if spec is None or spec.sizes.get("pass", 0) < 2:
        return None
    with run.pass_table() as ps:
        traffic = ps["traffic"].values if "traffic" in ps else ps["pass"].values
        rate = ps["growth_rate"].load() if "growth_rate" in ps else None
    wl_dim = [d for d in spec.dims if d != "pass"][0]
    wl_mm = values_in(spec[wl_dim], "mm")
    keep = np.nanmax(spec.values, axis=0) > 1e-3 * np.nanmax(spec.values)
    fig = Figure(figsize=(9, 6 if rate is not None else 4), layout="constrained")
    axes = fig.subplots(2 if rate is not None else 1, 1, squeeze=False)[:, 0]
    ordered = spec.transpose(wl_dim, "pass")
    try:
        amp, label = values_in(ordered, "um")[keep], "amplitude (µm)"
    except ValueError:  # a spectrum in other units (e.g. a PSD) is drawn as stored
        amp, label = ordered.values[keep], f"{spec.attrs.get('long_name', 'spectrum')} ({spec.attrs.get('units', '?')})"
    mesh = axes[0].pcolormesh(traffic, wl_mm[keep], amp, shading="nearest", cmap="magma")
    fig.colorbar(mesh, ax=axes[0], label=label)
    what = "contact-filtered " if spec.name == "filtered_spectrum" else ""
    axes[0].set(yscale="log", xlabel="traffic (passages)", ylabel="wavelength (mm)",
                title=f"Corrugation {what}spectrum over traffic\ncontact model: {run.contact_model}")
    if rate is not None:
        mean_rate = rate.mean("pass").values
        # Rates of harmonics far below the dominant ones are noise in dB, and a
        # harmonic built up from nothing has no meaningful rate: keep those
        # present from the first passage (any time, if none was).
        first = spec.values[0]
        strong = first > 0.05 * np.nanmax(first) if np.nanmax(first) > 0 else \
            np.nanmax(spec.values, axis=0) > 0.05 * np.nanmax(spec.values)
        axes[1].semilogx(wl_mm[strong], mean_rate[strong], "o-", ms=3)
        axes[1].axhline(0.0, color="k", lw=0.8)
        axes[1].set(xlabel="wavelength (mm)", ylabel="growth rate (dB / 1e5 passages)",
                    title="mean growth rate over the run (harmonics above 5 % of the largest at the first passage)")
        axes[1].grid(alpha=0.3, which="both")
    return _save(fig, out_dir, "spectrogram.png")


class FigureSkipped(Exception):
    """A figure the run file was configured not to support (a note, not a problem)."""


FigureFn = Callable[[Run, int, Path], "Path | None"]
RAIL_FIGURES: tuple[FigureFn, ...] = (wear_map, wear_centreline)
CONTACT_FIGURES: tuple[FigureFn, ...] = (loads, traction_snapshots)
OPTIONAL_FIGURES: tuple[FigureFn, ...] = (spectrum, rms_growth, spectrogram, profile_snapshots)


def contact_pass_for(run: Run, pass_index: int) -> int | None:
    """The stored index whose contact history the contact figures draw: the
    passage's own, else the latest one before it, else the first after it."""
    kept = run.contact_passes()
    if not kept:
        return None
    if pass_index in kept:
        return pass_index
    before = [p for p in kept if p < pass_index]
    return before[-1] if before else kept[0]


def make_figures(path, out_dir, pass_number: int | None = None, levels_at: list[int] | None = None):
    """Write every figure of one run that its contents allow.

    ``pass_number`` counts passages from 1 as the terminal does (default: the
    last stored); ``levels_at`` the passages of the band-level figure
    (default: spread over the run).  Returns ``(paths, problems, notes)``:
    the PNGs written, one message per figure that could not be made (a
    defect of the file), and one per figure left out or drawn for another
    passage because the run did not store what it needs (not a problem).
    Raises RunFileError when the file itself is unusable.
    """
    from . import levels

    run = Run.open(path)
    pass_index = run.resolve_pass(pass_number)
    out_dir = Path(out_dir)
    todo = [(fn, pass_index) for fn in RAIL_FIGURES]
    notes = []
    contact = contact_pass_for(run, pass_index)
    if contact is None:
        notes.append(f"{run.path}: no contact history stored (growth.contact_history); "
                     "loads.png and traction_snapshots.png skipped")
    else:
        if contact != pass_index:
            notes.append(f"{run.path}: passage {pass_index + 1} has no contact history; loads.png and "
                         f"traction_snapshots.png show passage {contact + 1}, the nearest one kept")
        todo += [(fn, contact) for fn in CONTACT_FIGURES]
    todo += [(fn, pass_index) for fn in OPTIONAL_FIGURES]

    def band_levels(r, _p, o):
        return levels.band_levels(r, o, levels_at)

    def level_growth(r, _p, o):
        return levels.level_growth(r, o)

    todo += [(band_levels, pass_index), (level_growth, pass_index)]
    paths, problems = [], []
    for fn, p in todo:
        name = fn.__name__
        try:
            written = fn(run, p, out_dir)
        except FigureSkipped as note:
            notes.append(f"{run.path}: {note}")
            continue
        except KeyError as err:
            problems.append(f"{run.path}: {name}: missing variable {err}")
            continue
        except (RunFileError, ValueError) as err:
            problems.append(f"{run.path}: {name}: {err}")
            continue
        if written is not None:
            paths.append(written)
    if not levels.has_levels(run):
        notes.append(f"{run.path}: no roughness levels (passes/roughness_level: written since issue 35); "
                     "levels.png and level_growth.png skipped")
    return paths, problems, notes
