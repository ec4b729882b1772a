"""The run-file contract, and a checker for it (``corrugation-post check``).

Only required content is listed: extra variables, attributes and groups are
allowed everywhere.  Contact groups are checked against ``CONTACT_VARS``.
A file of two rails (root group ``second_rail``) has the second rail's
``rail``, ``passes`` and ``contact`` groups checked like the root's, and
the same passages and traffic as the first rail (``check_second_rail``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from . import io

ROOT_ATTRS = ("config", "version", "title", "contact_model")

# group -> {variable: dims}; coordinates are listed like variables.
RAIL_VARS = {
    "x": ("x",), "y": ("y",), "pass": ("pass",),
    "traffic": ("pass",),
    "profile": ("pass", "y", "x"),
    "wear": ("pass", "y", "x"),
}
PASSES_VARS = {
    "pass": ("pass",),
    "traffic": ("pass",),
    "rms_corrugation": ("pass",),
    "cpu_seconds": ("pass",),
}
_STEP = ("time", "x_c", "normal_force", "longitudinal_force", "creepage_x", "creepage_y",
         "spin", "semi_axis_a", "semi_axis_b", "max_pressure", "contact_area", "stick_fraction")
_ELEMENT = ("xi", "eta", "d_xi", "d_eta")
FIELDS = ("pressure", "traction_x", "traction_y", "slip_x", "slip_y", "wear_rate", "stick")
CONTACT_VARS = {
    "step": ("step",), "element": ("element",),
    **{v: ("step",) for v in _STEP},
    **{v: ("element",) for v in _ELEMENT},
    **{v: ("step", "element") for v in FIELDS},
}
# A contact group without element fields (output.store_fields = false).
CONTACT_STEP_VARS = {k: v for k, v in CONTACT_VARS.items() if k not in FIELDS}
# Expected units (canonical spelling, see units.normalise).
UNITS = {
    "x": "m", "y": "m", "profile": "m", "wear": "m", "rms_corrugation": "m",
    "cpu_seconds": "s", "time": "s", "x_c": "m", "normal_force": "N",
    "longitudinal_force": "N", "creepage_x": "1", "creepage_y": "1", "spin": "1/m",
    "semi_axis_a": "m", "semi_axis_b": "m", "max_pressure": "Pa", "contact_area": "m2",
    "stick_fraction": "1",
    "xi": "1", "eta": "1", "d_xi": "1", "d_eta": "1",
    "element_x": "m", "element_y": "m", "element_dx": "m", "element_dy": "m",
    "pressure": "Pa", "traction_x": "Pa", "traction_y": "Pa",
    "slip_x": "m/s", "slip_y": "m/s", "wear_rate": "m/s", "stick": "1",
}


def expected_groups(path: str | Path) -> dict[str, dict[str, tuple[str, ...]]]:
    """Group path -> required variables, including every stored contact
    group, of every rail of the file."""
    groups = {}
    for rail in io.rails(path):
        groups |= rail_groups(path, rail.prefix)
    return groups


def rail_groups(path: str | Path, prefix: str = "") -> dict[str, dict[str, tuple[str, ...]]]:
    """Group path -> required variables of one rail (groups under ``prefix``)."""
    groups = {prefix + io.RAIL: RAIL_VARS, prefix + io.PASSES: PASSES_VARS}
    for p in io.contact_passes(path, prefix):
        group = prefix + io.contact_group(p)
        groups[group] = CONTACT_VARS if _has_fields(path, group) else CONTACT_STEP_VARS
    return groups


def _has_fields(path, group: str) -> bool:
    """Whether a contact group holds the element fields (a run with
    ``output.store_fields = false`` keeps the per-step values only)."""
    import h5py

    with h5py.File(path, "r") as f:
        return any(v in f[group] for v in FIELDS)


def check_dataset(ds: xr.Dataset, group: str, required: dict[str, tuple[str, ...]]) -> list[str]:
    """Problems with one opened group (empty list when it follows the contract)."""
    from .units import normalise

    problems = []
    phony = [d for d in ds.dims if str(d).startswith("phony_dim")]
    if phony:
        problems.append(f"{group}: dimensions without dimension scales: {phony}")
    for name, dims in required.items():
        if name not in ds.variables:
            problems.append(f"{group}: missing variable '{name}'{dims}")
        elif tuple(ds[name].dims) != dims:
            problems.append(f"{group}/{name}: dims {tuple(ds[name].dims)}, expected {dims}")
    for name, var in ds.variables.items():
        for attr in ("units", "long_name"):
            if attr not in var.attrs:
                problems.append(f"{group}/{name}: no '{attr}' attribute")
        want = UNITS.get(str(name))
        if want and "units" in var.attrs and normalise(var.attrs["units"]) != want:
            problems.append(f"{group}/{name}: units {var.attrs['units']!r}, expected {want!r}")
    return problems


def check_grid(ds: xr.Dataset, group: str) -> list[str]:
    """Fixed-grid rules: uniform elements, row by row (y increasing), each row
    leading edge (x > 0) first, xi and eta the coordinates over the mean patch."""
    x, y = ds["element_x"].values, ds["element_y"].values
    dx, dy = ds["element_dx"].values, ds["element_dy"].values
    problems = []
    if np.any(dx <= 0) or np.any(dy <= 0) or np.ptp(dx) > 1e-12 * dx.max() or np.ptp(dy) > 1e-12 * dy.max():
        problems.append(f"{group}: fixed-grid elements not uniform and positive")
        return problems
    rows = np.unique(y.round(12))
    nx = x.size // max(rows.size, 1)
    if rows.size * nx != x.size:
        problems.append(f"{group}: {x.size} elements are not {rows.size} rows of equal length")
        return problems
    if np.any(np.diff(y.reshape(rows.size, nx)[:, 0]) <= 0):
        problems.append(f"{group}: grid rows not ordered by increasing y")
    if np.any(np.diff(x.reshape(rows.size, nx), axis=1) >= 0):
        problems.append(f"{group}: grid rows not ordered leading edge (x>0) first")
    xi = ds["xi"].values
    k = int(np.argmax(np.abs(x)))
    a = x[k] / xi[k] if xi[k] != 0 else np.nan
    if not (a > 0 and np.allclose(xi * a, x, rtol=1e-9, atol=1e-15)):
        problems.append(f"{group}: xi is not element_x over one semi-axis")
    return problems


def check_mesh(ds: xr.Dataset, group: str) -> list[str]:
    """Contact mesh rules: unit-circle elements, strips of equal length, leading edge first
    (on the adapted mesh), or the fixed grid's rules."""
    if not all(v in ds.variables for v in _ELEMENT):
        return []
    if "element_x" in ds.variables:
        problems = check_grid(ds, group)
        if "stick" in ds.variables and not np.isin(np.unique(ds["stick"].values), (0, 1)).all():
            problems.append(f"{group}/stick: values other than 0 and 1")
        return problems
    xi, eta = ds["xi"].values, ds["eta"].values
    problems = []
    if np.any(xi**2 + eta**2 > 1.0 + 1e-9):
        problems.append(f"{group}: element centres outside the unit circle xi^2 + eta^2 <= 1")
    if np.any(ds["d_xi"].values <= 0) or np.any(ds["d_eta"].values <= 0):
        problems.append(f"{group}: non-positive d_xi or d_eta")
    starts = np.flatnonzero(np.r_[True, ~np.isclose(np.diff(eta), 0.0, atol=1e-12)])
    lengths = np.diff(np.r_[starts, eta.size])
    if len(set(eta[starts].round(9))) != starts.size:
        problems.append(f"{group}: elements are not ordered strip by strip")
    if np.unique(lengths).size > 1:
        problems.append(f"{group}: strips have different numbers of elements {sorted(set(lengths))}")
    for s, n in zip(starts, lengths):
        if n > 1 and np.any(np.diff(xi[s : s + n]) >= 0):
            problems.append(f"{group}: strip at eta={eta[s]:.3g} not ordered leading edge (xi>0) first")
            break
    if "stick" in ds.variables and not np.isin(np.unique(ds["stick"].values), (0, 1)).all():
        problems.append(f"{group}/stick: values other than 0 and 1")
    return problems


# The band levels (passes group, written since issue 35): dims and units.
LEVEL_VARS = {
    "band": ("band",), "band_lower": ("band",), "band_upper": ("band",),
    "initial_level": ("band",), "limit_level": ("band",),
    "roughness_level": ("pass", "band"), "level_rate": ("pass", "band"),
    "passages_to_limit": ("pass", "band"),
}
LEVEL_UNITS = {
    "band": "m", "band_lower": "m", "band_upper": "m", "initial_level": "dB", "limit_level": "dB",
    "roughness_level": "dB", "level_rate": "dB/1e5 passages", "passages_to_limit": "1",
    "traffic_mgt": "Mt", "traffic_days": "d", "mgt_to_limit": "Mt", "days_to_limit": "d",
}


def check_levels(path: str | Path, prefix: str = "") -> list[str]:
    """The band levels, where the file has them: all of them, on their dims,
    with their units, no NaN (inf only where the contract allows it)."""
    group = prefix + io.PASSES
    with io.open_group(path, group) as ps:
        if "roughness_level" not in ps.variables:
            return []
        problems = []
        for name, dims in LEVEL_VARS.items():
            if name not in ps.variables:
                problems.append(f"{group}: missing variable '{name}'{dims}")
            elif tuple(ps[name].dims) != dims:
                problems.append(f"{group}/{name}: dims {tuple(ps[name].dims)}, expected {dims}")
        for name, unit in LEVEL_UNITS.items():
            if name in ps.variables and ps[name].attrs.get("units") != unit:
                problems.append(f"{group}/{name}: units {ps[name].attrs.get('units')!r}, expected {unit!r}")
            if name in ps.variables and np.isnan(ps[name].values).any():
                problems.append(f"{group}/{name}: NaN values")
        for name in ("roughness_level", "level_rate", "initial_level", "band"):
            if name in ps.variables and not np.isfinite(ps[name].values).all():
                problems.append(f"{group}/{name}: non-finite values")
        return problems


def check_second_rail(path: str | Path) -> list[str]:
    """A two-rail file: both rails named, apart, and the second rail's
    passages and traffic those of the first (the rails share the passages)."""
    import h5py

    with h5py.File(path, "r") as f:
        second = f[io.SECOND_RAIL]
        problems = [f"{where}: missing attribute 'rail_name' (the file has a second rail)"
                    for where, obj in (("root", f), (io.SECOND_RAIL, second)) if "rail_name" not in obj.attrs]
        names = [io.as_str(obj.attrs.get("rail_name")) for obj in (f, second)]
        if names[0] is not None and names[0] == names[1]:
            problems.append(f"{io.SECOND_RAIL}: rail_name {names[1]!r} is the first rail's too")
        # A missing group is reported by the groups' own check (cannot open).
        for group in (g for g in (io.RAIL, io.PASSES) if isinstance(second.get(g), h5py.Group)):
            problems += _same_as_first(f, group, "pass") + _same_as_first(f, group, "traffic")
    return problems


def _same_as_first(f, group: str, name: str) -> list[str]:
    """The second rail's ``group/name`` against the first rail's (values equal)."""
    first, second = f.get(f"{group}/{name}"), f.get(f"{io.SECOND_PREFIX}{group}/{name}")
    if first is None or second is None:
        return []  # a missing variable is reported by the group's own check
    a, b = np.asarray(first[()]), np.asarray(second[()])
    where = f"{io.SECOND_PREFIX}{group}/{name}"
    if a.shape != b.shape:
        what = "passages" if name == "pass" else "values"
        return [f"{where}: {b.size} {what}, the first rail's {group}/{name} has {a.size}"]
    if not np.array_equal(a, b):
        return [f"{where}: differs from the first rail's {group}/{name} (the rails share the passages)"]
    return []


def check_file(path: str | Path) -> list[str]:
    """All contract problems found in a run file (empty list when it conforms)."""
    path = io.check_run_file(path)
    attrs = io.root_attrs(path)
    problems = [f"root: missing attribute '{a}'" for a in ROOT_ATTRS if a not in attrs]
    if "config" in attrs:
        try:
            cfg = io.parse_config(str(attrs["config"]), path)
            io.friction_coefficient(cfg, path)
        except io.RunFileError as err:
            problems.append(f"root: {err}")
    # Contact histories are kept for the passages growth.contact_history
    # names (none at all with contact_history = []): the rail snapshots of
    # the other passages need none.
    groups = expected_groups(path)
    prefixes = [rail.prefix for rail in io.rails(path)]
    if len(prefixes) > 1:
        problems += check_second_rail(path)
    for prefix in prefixes:
        try:
            problems += check_levels(path, prefix)
        except io.RunFileError:
            if not prefix:
                raise
            # The second rail without passes: reported with its groups below.
    for group, required in groups.items():
        try:
            with io.open_group(path, group) as ds:
                problems += check_dataset(ds, group, required)
                problems += check_mesh(ds, group)
                for name in ("traffic",):
                    if name in ds and np.any(np.diff(ds[name].values) < 0):
                        problems.append(f"{group}/{name}: not cumulative (decreases)")
        except io.RunFileError as err:
            problems.append(str(err))
    return problems
