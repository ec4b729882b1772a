"""Figures of one run: wear maps (paper Figs. 6-8), loads, traction snapshots
(Figs. 3-4), growth, and the roughness levels against their limit
(``levels.py``).

Every figure function takes a ``Run``, a stored passage index (the ``pass``
coordinate, from 0) and an output folder, writes one PNG and returns its
path.  In a file of two rails the figures of one passage's wear and contact
(and the profile snapshots) are drawn per rail, titled with the rail's name,
the second rail's files ending in ``_second_rail``; the growth figures
(spectrum, rms, spectrogram, levels) draw both rails in one figure, lines
labelled by rail name (``BOTH_RAILS``).  Titles number passages from 1, as the terminal does; lengths are in
mm, roughness in µm or dB re 1 µm.  Figures are built on
``matplotlib.figure.Figure`` objects (no pyplot, no display needed).
"""

from __future__ import annotations

from pathlib import Path
from typing import Callable

import numpy as np
from matplotlib.colors import LogNorm
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator
from matplotlib.tri import Triangulation

from .io import Run, RunFileError
from .schema import FIELDS
from .units import depth_unit, values_in

DPI = 150


def _rail_prefix(run: Run) -> str:
    """The rail a figure of one rail of a two-rail file shows ("" in a one-rail file)."""
    return f"{run.rail_name}: " if run.rail_name else ""


def _rail_label(run: Run) -> dict:
    """A line's label naming its rail, in a two-rail file."""
    return {"label": run.rail_name} if run.rail_name else {}


def _title(run: Run, what: str, pass_index: int, note: str = "", rail: bool = True) -> str:
    named = _rail_prefix(run) if rail else ""
    return f"{named}{what}, passage {pass_index + 1}{note}\ncontact model: {run.contact_model}"


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
    return (f"{_rail_prefix(run)}Wear depth of passage {pass_index + 1} alone: one wheel passage, unscaled{seen}\n"
            f"contact model: {run.contact_model}")


def wear_map(run: Run, pass_index: int, out_dir: Path) -> Path:
    """Wear depth of one passage over the rail stretch, colour in nm or µm (by
    its size), and below it the variation along the rail that grows or
    wears corrugation: each lateral row's depth minus its mean along x, on
    its own diverging scale (a variation of a percent is invisible on the
    depth's scale)."""
    with run.rail() as rail:
        wear = rail["wear"].sel({"pass": pass_index}).transpose("y", "x").load()
        x, y = values_in(rail["x"], "mm"), values_in(rail["y"], "mm")
        note = _traffic_note(rail, pass_index)
    fig = Figure(figsize=(9, 6.5), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True)
    unit, label = depth_unit(wear)
    mesh = top.pcolormesh(x, y, values_in(wear, unit), shading="auto", cmap="viridis")
    fig.colorbar(mesh, ax=top, label=f"wear depth ({label})")
    top.set(ylabel="y lateral (mm)", title=_wear_title(run, pass_index, note))
    variation = (wear - wear.mean("x")).assign_attrs(units=wear.attrs["units"])
    vunit, vlabel = depth_unit(variation)
    v = values_in(variation, vunit)
    peak = float(np.nanmax(np.abs(v))) if np.size(v) else 0.0
    # Against the deepest row's mean depth (the centre of the running band).
    deepest = float(np.nanmax(values_in(wear, vunit).mean(axis=1))) if np.size(v) else 0.0
    share = peak / deepest * 100 if deepest > 0 else float("nan")
    mesh = bottom.pcolormesh(x, y, v, shading="auto", cmap="RdBu_r", vmin=-peak or None, vmax=peak or None)
    fig.colorbar(mesh, ax=bottom, label=f"depth minus its mean along x ({vlabel})")
    bottom.set(xlabel="x along rail (mm)", ylabel="y lateral (mm)",
               title=f"its variation along the rail, up to {share:.2g} % of the centre's mean depth")
    return _save(fig, out_dir, f"wear_map{run.suffix}.png")


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
    return _save(fig, out_dir, f"wear_centreline{run.suffix}.png")


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
    return _save(fig, out_dir, f"loads{run.suffix}.png")


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
                            f"traction_snapshots{run.suffix}.png skipped")
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
    return _save(fig, out_dir, f"traction_snapshots{run.suffix}.png")


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


def _passage_spectrum(run: Run, pass_index: int):
    """The rail's spectrum(pass, wavelength) at ``pass_index``, or None."""
    spec = _find_spectrum(run)
    if spec is None or pass_index not in spec["pass"].values:
        return None
    return spec.sel({"pass": pass_index})


def _plot_spectrum(ax, spec, label: dict) -> tuple[str, str]:
    """One rail's spectrum on ``ax``; returns the axis labels (x, y).
    Amplitudes in µm, wavelengths in mm (the units of the other figures); a
    spectrum in other units (a PSD) is drawn as stored."""
    wl = spec[spec.dims[0]]
    try:
        y, ylabel = values_in(spec, "um"), "amplitude (µm)"
    except ValueError:
        y, ylabel = spec.values, f"{spec.attrs.get('long_name', 'spectrum')} ({spec.attrs.get('units', '?')})"
    try:
        ax.semilogx(values_in(wl, "mm"), y, "o-", ms=2, **label)
        return f"{wl.name} (mm)", ylabel
    except ValueError:
        ax.semilogx(wl.values, y, "o-", ms=2, **label)
        return f"{wl.name} ({wl.attrs.get('units', '?')})", ylabel


def spectrum(run: Run, pass_index: int, out_dir: Path) -> Path | None:
    """spectrum(pass, wavelength) of the chosen passage, if the run file has
    one; every rail's on the same axes."""
    found = [(r, sp) for r in run.rails() if (sp := _passage_spectrum(r, pass_index)) is not None]
    if not found:
        return None
    fig = Figure(figsize=(8, 4), layout="constrained")
    ax = fig.add_subplot()
    for r, spec in found:
        xlabel, ylabel = _plot_spectrum(ax, spec, _rail_label(r))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3, which="both")
    if run.two_rails:
        ax.legend(fontsize=8)
    ax.set_title(_title(run, "Centre-line corrugation amplitude spectrum", pass_index, rail=False))
    return _save(fig, out_dir, "spectrum.png")


def _rms_series(run: Run) -> dict | None:
    """The rail's traffic, rms corrugation (µm) and, when the file has them,
    traffic scale and update ratio; None with fewer than two passages."""
    with run.pass_table() as ps:
        if "rms_corrugation" not in ps or ps.sizes.get("pass", 0) < 2:
            return None
        series = {"traffic": ps["traffic"].values if "traffic" in ps else ps["pass"].values,
                  "rms": values_in(ps["rms_corrugation"], "um")}
        if "traffic_scale" in ps and "update_ratio" in ps:
            series |= {"scale": ps["traffic_scale"].values, "ratio": ps["update_ratio"].values}
        return series


def rms_growth(run: Run, pass_index: int, out_dir: Path) -> Path | None:
    """RMS corrugation vs traffic, when more than one passage is recorded
    (every rail's, labelled by rail); with the traffic scale m and the update
    ratio (its stability criterion) below when the run file has them."""
    found = [(r, sr) for r in run.rails() if (sr := _rms_series(r)) is not None]
    if not found:
        return None
    scaling = all("scale" in sr for _, sr in found)
    extra = 0.5 * (len(found) - 1)  # a title line per rail
    fig = Figure(figsize=(8, (6 if scaling else 4) + extra), layout="constrained")
    axes = fig.subplots(2 if scaling else 1, 1, squeeze=False, sharex=True)[:, 0]
    for r, sr in found:
        axes[0].plot(sr["traffic"], sr["rms"], "o-", ms=3, **_rail_label(r))
    trends = "\n".join(_rms_trend(sr["rms"], sr["traffic"], r.rail_name) for r, sr in found)
    axes[0].set(ylabel="rms corrugation (µm)", title=f"{trends}\ncontact model: {run.contact_model}")
    axes[0].grid(alpha=0.3)
    if run.two_rails:
        axes[0].legend(fontsize=8)
    if scaling:
        _scaling_panel(axes[1], found)
    axes[-1].set_xlabel("traffic (wheel passages)")
    return _save(fig, out_dir, "rms_corrugation.png")


def _regime_series(run: Run) -> dict | None:
    """The rail's traffic, its wear law's regime names and each passage's
    share of the wear volume per regime (``passes/wear_regime_share``);
    None where the file has no shares or the law has one regime."""
    with run.pass_table() as ps:
        if "wear_regime_share" not in ps or ps.sizes.get("wear_regime", 0) < 2:
            return None
        meanings = str(ps["wear_regime"].attrs.get("flag_meanings", "")).split()
        count = ps.sizes["wear_regime"]
        names = meanings if len(meanings) == count else [f"regime {k + 1}" for k in range(count)]
        return {"traffic": ps["traffic"].values if "traffic" in ps else ps["pass"].values,
                "share": ps["wear_regime_share"].transpose("pass", "wear_regime").values, "names": names}


def wear_regimes(run: Run, pass_index: int, out_dir: Path) -> Path | None:
    """Each passage's wear volume by regime of the wear law (the
    frictional-work law's mild, severe and catastrophic; the wear map's
    regions), stacked to 1, against traffic; a panel per rail. None where
    the run's wear law has a single regime (Archard's)."""
    found = [(r, sr) for r in run.rails() if (sr := _regime_series(r)) is not None]
    if not found:
        return None
    fig = Figure(figsize=(8, 3.2 * len(found)), layout="constrained")
    axes = fig.subplots(len(found), 1, squeeze=False, sharex=True)[:, 0]
    for ax, (r, sr) in zip(axes, found):
        ax.stackplot(sr["traffic"], np.nan_to_num(sr["share"]).T, labels=sr["names"], alpha=0.85)
        ax.set(ylim=(0, 1), ylabel="share of the wear volume",
               title=f"Wear by regime{(' - ' + r.rail_name) if run.two_rails else ''}")
        ax.legend(fontsize=8, loc="upper right")
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("traffic (wheel passages)")
    return _save(fig, out_dir, "wear_regimes.png")


def _scaling_panel(ax, found) -> None:
    """The traffic scale m (shared by the rails) and each rail's update ratio q."""
    first = found[0][1]
    ax.semilogy(first["traffic"], first["scale"], "o-", ms=3, label="traffic scale m (passages per update)")
    ax.set_ylabel("traffic scale m\n(wheel passages per simulated passage)")
    twin = ax.twinx()
    for (r, sr), line in zip(found, ("s-", "s--")):
        label = f"update ratio q ({r.rail_name})" if r.rail_name else "update ratio q"
        twin.plot(sr["traffic"], sr["ratio"], line, ms=2, color="tab:red", label=label)
    twin.set_ylabel("update ratio q\n(largest wear step / roughness, per harmonic)", color="tab:red")
    ax.grid(alpha=0.3)


def _rms_trend(rms_um: np.ndarray, traffic: np.ndarray, rail: str = "") -> str:
    """What the rms does over the run, in words: grows, falls or holds
    (on ``rail``, named first, in a two-rail file)."""
    subject = f"{rail}: the rms corrugation" if rail else "The rms corrugation"
    first, last = float(rms_um[0]), float(rms_um[-1])
    if first > 0 and abs(last / first - 1) < 0.01:
        verb = "holds at"
        return f"{subject} {verb} {last:.3g} µm over {traffic[-1]:.3g} wheel passages"
    verb = "grows" if last > first else "falls"
    return f"{subject} {verb} from {first:.3g} to {last:.3g} µm over {traffic[-1]:.3g} wheel passages"


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
           title=f"{_rail_prefix(run)}Rail profile on the centre line at stored passages\n"
                 f"contact model: {run.contact_model}")
    ax.legend(fontsize=8, ncols=2)
    ax.grid(alpha=0.3)
    return _save(fig, out_dir, f"profile_snapshots{run.suffix}.png")


def _spectrogram_data(run: Run) -> dict | None:
    """The rail's spectrum over traffic (contact-filtered where the file has
    it), its traffic and growth rates; None with fewer than two passages."""
    spec = _find_spectrum(run, ("filtered_spectrum", "spectrum"))
    if spec is None or spec.sizes.get("pass", 0) < 2:
        return None
    with run.pass_table() as ps:
        traffic = ps["traffic"].values if "traffic" in ps else ps["pass"].values
        rate = ps["growth_rate"].load() if "growth_rate" in ps else None
    wl_dim = [d for d in spec.dims if d != "pass"][0]
    return {"run": run, "spec": spec, "traffic": traffic, "rate": rate, "wl_dim": wl_dim,
            "wl_mm": values_in(spec[wl_dim], "mm")}


def _amplitude_map(d: dict) -> tuple[np.ndarray, np.ndarray, str]:
    """The kept wavelengths (mm), the amplitudes on them (wavelength, pass) and their label."""
    spec = d["spec"]
    keep = np.nanmax(spec.values, axis=0) > 1e-3 * np.nanmax(spec.values)
    ordered = spec.transpose(d["wl_dim"], "pass")
    try:
        amp, label = values_in(ordered, "um")[keep], "amplitude (µm)"
    except ValueError:  # a spectrum in other units (e.g. a PSD) is drawn as stored
        amp, label = ordered.values[keep], f"{spec.attrs.get('long_name', 'spectrum')} ({spec.attrs.get('units', '?')})"
    return d["wl_mm"][keep], amp, label


# The spectrogram's colour range: from this fraction of the largest
# amplitude to it (three decades, 60 dB).
SPECTROGRAM_DECADES = 1e-3


def _spectrogram_panel(fig, ax, d: dict, scale: dict) -> None:
    """One rail's amplitude over wavelength and traffic (``scale``: the
    colour limits shared by the rails, empty with one rail)."""
    wl_mm, amp, label = _amplitude_map(d)
    # A log colour scale over three decades below the largest amplitude
    # (shared by the rails): one strong line does not swamp the rest, and
    # what lies below the decades is drawn as their floor.
    top = scale.get("vmax", float(np.nanmax(amp)))
    if top > 0:
        norm = LogNorm(vmin=top * SPECTROGRAM_DECADES, vmax=top)
        mesh = ax.pcolormesh(d["traffic"], wl_mm, np.clip(amp, top * SPECTROGRAM_DECADES, None), shading="nearest",
                             cmap="magma", norm=norm)
        label = f"{label}, log scale"
    else:
        mesh = ax.pcolormesh(d["traffic"], wl_mm, amp, shading="nearest", cmap="magma", **scale)
    fig.colorbar(mesh, ax=ax, label=label)
    run = d["run"]
    what = "contact-filtered " if d["spec"].name == "filtered_spectrum" else ""
    ax.set(yscale="log", xlabel="traffic (wheel passages)", ylabel="wavelength (mm)",
           title=f"{_rail_prefix(run)}Corrugation {what}spectrum over traffic\ncontact model: {run.contact_model}")


def _rate_line(ax, d: dict) -> None:
    """One rail's growth rate per wavelength averaged over the run.  Rates of
    harmonics far below the dominant ones are noise in dB, and a harmonic
    built up from nothing has no meaningful rate: keep those present from
    the first passage (any time, if none was)."""
    spec = d["spec"]
    mean_rate = d["rate"].mean("pass").values
    first = spec.values[0]
    strong = first > 0.05 * np.nanmax(first) if np.nanmax(first) > 0 else \
        np.nanmax(spec.values, axis=0) > 0.05 * np.nanmax(spec.values)
    ax.semilogx(d["wl_mm"][strong], mean_rate[strong], "o-", ms=3, **_rail_label(d["run"]))


def spectrogram(run: Run, pass_index: int, out_dir: Path) -> Path | None:
    """Corrugation amplitude against wavelength and traffic (growth studies),
    with the growth rate per wavelength averaged over the run when present.
    Uses the contact-filtered spectrum (what the wheel sees, on which the
    growth rates are computed) when the file has it.  Two rails: one map
    per rail (one colour scale), their growth rates on one axes."""
    found = [d for r in run.rails() if (d := _spectrogram_data(r)) is not None]
    if not found:
        return None
    rated = [d for d in found if d["rate"] is not None]
    height = (6 if rated else 4) if len(found) == 1 else 3.5 * len(found) + (3 if rated else 0)
    fig = Figure(figsize=(9, height), layout="constrained")
    axes = fig.subplots(len(found) + bool(rated), 1, squeeze=False)[:, 0]
    scale = _shared_scale([_amplitude_map(d)[1] for d in found]) if len(found) > 1 else {}
    for ax, d in zip(axes, found):
        _spectrogram_panel(fig, ax, d, scale)
    if rated:
        for d in rated:
            _rate_line(axes[-1], d)
        axes[-1].axhline(0.0, color="k", lw=0.8)
        axes[-1].set(xlabel="wavelength (mm)", ylabel="growth rate (dB / 1e5 passages)",
                     title="mean growth rate over the run (harmonics above 5 % of the largest at the first passage)")
        axes[-1].grid(alpha=0.3, which="both")
        if run.two_rails:
            axes[-1].legend(fontsize=8)
    return _save(fig, out_dir, "spectrogram.png")


def _shared_scale(maps: list[np.ndarray]) -> dict:
    """The colour limits that cover every rail's map."""
    return {"vmin": min(float(np.nanmin(m)) for m in maps), "vmax": max(float(np.nanmax(m)) for m in maps)}


class FigureSkipped(Exception):
    """A figure the run file was configured not to support (a note, not a problem)."""


FigureFn = Callable[[Run, int, Path], "Path | None"]
RAIL_FIGURES: tuple[FigureFn, ...] = (wear_map, wear_centreline)
CONTACT_FIGURES: tuple[FigureFn, ...] = (loads, traction_snapshots)
OPTIONAL_FIGURES: tuple[FigureFn, ...] = (spectrum, rms_growth, spectrogram, profile_snapshots, wear_regimes)
# The figures that draw every rail of a file in one figure; the others are
# drawn once per rail.
BOTH_RAILS: tuple[FigureFn, ...] = (spectrum, rms_growth, spectrogram, wear_regimes)


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


def _where(run: Run) -> str:
    """The file, and the rail in a two-rail file, for notes and problems."""
    return f"{run.path} ({run.rail_name})" if run.rail_name else f"{run.path}"


def _rail_todo(run: Run, pass_index: int) -> tuple[list, list[str]]:
    """One rail's wear and contact figures (the contact ones of the nearest
    passage with a contact history), and the notes on what it left out."""
    todo = [(fn, run, pass_index, _where(run)) for fn in RAIL_FIGURES]
    names = f"loads{run.suffix}.png and traction_snapshots{run.suffix}.png"
    contact = contact_pass_for(run, pass_index)
    if contact is None:
        return todo, [f"{_where(run)}: no contact history stored (growth.contact_history); {names} skipped"]
    notes = []
    if contact != pass_index:
        notes.append(f"{_where(run)}: passage {pass_index + 1} has no contact history; {names} "
                     f"show passage {contact + 1}, the nearest one kept")
    return todo + [(fn, run, contact, _where(run)) for fn in CONTACT_FIGURES], notes


def _draw(todo, out_dir: Path) -> tuple[list[Path], list[str], list[str]]:
    """Draws ``todo`` ((figure, rail, passage, where) tuples: ``where`` names
    the file, and the rail of a figure of one rail, in messages); returns the
    paths written, the problems and the notes."""
    paths, problems, notes = [], [], []
    for fn, run, p, where in todo:
        name = fn.__name__
        try:
            written = fn(run, p, out_dir)
        except FigureSkipped as note:
            notes.append(f"{where}: {note}")
            continue
        except KeyError as err:
            problems.append(f"{where}: {name}: missing variable {err}")
            continue
        except (RunFileError, ValueError) as err:
            problems.append(f"{where}: {name}: {err}")
            continue
        if written is not None:
            paths.append(written)
    return paths, problems, notes


def make_figures(path, out_dir, pass_number: int | None = None, levels_at: list[int] | None = None):
    """Write every figure of one run that its contents allow.

    ``pass_number`` counts passages from 1 as the terminal does (default: the
    last stored); ``levels_at`` the passages of the band-level figure
    (default: spread over the run).  Returns ``(paths, problems, notes)``:
    the PNGs written, one message per figure that could not be made (a
    defect of the file), and one per figure left out or drawn for another
    passage because the run did not store what it needs (not a problem).
    A two-rail file has each rail's own figures (``BOTH_RAILS`` excepted).
    Raises RunFileError when the file itself is unusable.
    """
    from . import levels

    run = Run.open(path)
    pass_index = run.resolve_pass(pass_number)
    todo, notes = [], []
    for rail in run.rails():
        rail_todo, rail_notes = _rail_todo(rail, pass_index)
        todo += rail_todo
        notes += rail_notes
    for fn in OPTIONAL_FIGURES:
        rails = [run] if fn in BOTH_RAILS else run.rails()
        todo += [(fn, r, pass_index, run.path if fn in BOTH_RAILS else _where(r)) for r in rails]

    def band_levels(r, _p, o):
        return levels.band_levels(r, o, levels_at)

    def level_growth(r, _p, o):
        return levels.level_growth(r, o)

    todo += [(band_levels, run, pass_index, run.path), (level_growth, run, pass_index, run.path)]
    paths, problems, drawn_notes = _draw(todo, Path(out_dir))
    notes += drawn_notes
    if not levels.has_levels(run):
        notes.append(f"{run.path}: no roughness levels (passes/roughness_level: written since issue 35); "
                     "levels.png and level_growth.png skipped")
    return paths, problems, notes
