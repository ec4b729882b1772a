"""A small synthetic run file following the run-file contract exactly.

Written with xarray + h5netcdf (dimension scales, netCDF-4 compatible), one
group at a time.  Physically plausible but not a simulation: a sinusoidal
wear pattern, Hertz-like pressure and a Carter-like traction with a stick
zone at the leading edge.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

FRICTION = 0.3
CONFIG = f"""\
title = "synthetic test run"

[material]
friction_coefficient = {FRICTION}

[vehicle]
speed = 30.0
"""
WAVELENGTH = 0.04  # m, of the synthetic corrugation pattern


def _var(dims, values, units, long_name):
    return xr.Variable(dims, np.asarray(values), {"units": units, "long_name": long_name})


def _mesh(n_strips: int, per_strip: int):
    """Normalised element centres on the unit circle: strips along xi, leading edge first."""
    d_eta = 2.0 / n_strips
    eta_c = -1.0 + (np.arange(n_strips) + 0.5) * d_eta
    xi, eta, d_xi = [], [], []
    for e in eta_c:
        half = np.sqrt(1.0 - e**2)
        dx = 2.0 * half / per_strip
        xi += list(half - (np.arange(per_strip) + 0.5) * dx)  # leading edge (xi > 0) first
        eta += [e] * per_strip
        d_xi += [dx] * per_strip
    return np.array(xi), np.array(eta), np.array(d_xi), np.full(len(xi), d_eta)


def rail_dataset(n_pass: int, wear_scale: float, nx: int = 81, ny: int = 17) -> xr.Dataset:
    x = np.linspace(0.0, 0.1, nx)
    y = np.linspace(-0.008, 0.008, ny)
    passes = np.arange(n_pass)
    traffic = np.cumsum(np.r_[1, np.full(n_pass - 1, 10)])[:n_pass]
    shape = (1 + 0.3 * np.sin(2 * np.pi * x / WAVELENGTH))[None, :] * np.exp(-(y / 0.004) ** 2)[:, None]
    wear = wear_scale * 1e-8 * shape[None] * (1 + 0.1 * passes)[:, None, None]
    increments = np.diff(np.r_[0, traffic])[:, None, None]
    profile = -np.cumsum(wear * increments, axis=0)
    return xr.Dataset(
        {
            "traffic": _var("pass", traffic, "1", "real passages represented (cumulative)"),
            "profile": _var(("pass", "y", "x"), profile, "m", "rail surface height change"),
            "wear": _var(("pass", "y", "x"), wear, "m", "wear depth of the passage"),
        },
        coords={
            "x": _var("x", x, "m", "position along the rail"),
            "y": _var("y", y, "m", "lateral position"),
            "pass": _var("pass", passes, "1", "stored passage index"),
        },
    )


def growth_variables(ds: xr.Dataset, scale: float) -> xr.Dataset:
    """What a growth study adds to ``passes``: the traffic scale, the update
    ratio, the contact-filtered spectrum and its growth rates (on the
    ``wavelength`` of ``spectrum``), and the band levels against a limit."""
    n_pass, wl = ds.sizes["pass"], ds["wavelength"].values
    shape = np.exp(-((np.log(wl / WAVELENGTH)) ** 2))
    amp = 1e-6 * scale * shape[None, :] * (1 + 0.5 * np.arange(n_pass))[:, None]
    increments = np.diff(np.r_[0, ds["traffic"].values])
    ds["traffic_scale"] = _var("pass", increments, "1", "real passages per simulated passage")
    ds["update_ratio"] = _var("pass", np.full(n_pass, 0.01 * scale), "1", "update ratio q")
    ds["filtered_spectrum"] = _var(("pass", "wavelength"), amp, "m",
                                   "amplitude spectrum of the contact-filtered profile")
    ds["growth_rate"] = _var(("pass", "wavelength"), np.full((n_pass, wl.size), 3.0 * scale), "dB/1e5 passages",
                             "growth rate of each filtered harmonic")
    return ds.merge(band_levels(n_pass, scale))


def band_levels(n_pass: int, scale: float) -> xr.Dataset:
    """Band levels (dB re 1 µm) of five one-third-octave bands rising by
    ``2 scale`` dB a passage towards a flat -10 dB limit."""
    band = 0.1 / 10 ** (np.arange(5) / 10)
    initial = np.array([-30.0, -20.0, -15.0, -25.0, -80.0])
    level = initial[None, :] + 2.0 * scale * (1 + np.arange(n_pass))[:, None]
    rate = np.full((n_pass, band.size), 2.0 * scale * 1e5 / 10)
    to_limit = np.maximum((-10.0 - level) / (2.0 * scale), 0.0)
    return xr.Dataset(
        {
            "band_lower": _var("band", band / 10 ** 0.05, "m", "band lower wavelength"),
            "band_upper": _var("band", band * 10 ** 0.05, "m", "band upper wavelength"),
            "initial_level": _var("band", initial, "dB", "roughness level before the first passage"),
            "limit_level": xr.Variable("band", np.full(band.size, -10.0),
                                       {"units": "dB", "long_name": "roughness limit", "limit_name": "synthetic"}),
            "roughness_level": _var(("pass", "band"), level, "dB", "roughness level re 1 um"),
            "level_rate": _var(("pass", "band"), rate, "dB/1e5 passages", "level growth rate"),
            "passages_to_limit": _var(("pass", "band"), to_limit, "1", "passages to the limit"),
        },
        coords={"band": _var("band", band, "m", "band centre wavelength")},
    )


def passes_dataset(rail: xr.Dataset, extras: bool) -> xr.Dataset:
    rms = np.sqrt((rail["profile"] - rail["profile"].mean(("y", "x"))) ** 2).mean(("y", "x"))
    ds = xr.Dataset(
        {
            "traffic": _var("pass", rail["traffic"].values, "1", "real passages represented (cumulative)"),
            "rms_corrugation": _var("pass", rms.values, "m", "rms corrugation depth"),
            "cpu_seconds": _var("pass", np.full(rail.sizes["pass"], 1.5), "s", "CPU time of the passage"),
        },
        coords={"pass": _var("pass", rail["pass"].values, "1", "stored passage index")},
    )
    if extras:
        wl = np.geomspace(0.01, 0.1, 12)
        spec = 1e-12 * np.exp(-((np.log(wl / WAVELENGTH)) ** 2))[None, :] * (1 + ds["pass"].values[:, None])
        ds["spectrum"] = _var(("pass", "wavelength"), spec, "m^2 m", "roughness power spectral density")
        ds = ds.assign_coords(wavelength=_var("wavelength", wl, "m", "wavelength"))
    return ds


def contact_dataset(pass_index: int, creep_scale: float, extras: bool,
                    n_steps: int = 40, n_strips: int = 8, per_strip: int = 10) -> xr.Dataset:
    x_c = np.linspace(0.01, 0.09, n_steps)
    time = (x_c - x_c[0]) / 30.0
    ripple = 1 + 0.1 * np.sin(2 * np.pi * x_c / WAVELENGTH) * (1 + 0.05 * pass_index)
    fn = 100e3 * ripple
    in_contact = np.ones(n_steps, dtype=np.int8)
    if extras:  # two steps out of contact at the start
        in_contact[:2] = 0
        fn[:2] = 0.0
    a = 6e-3 * (fn / 1e5) ** (1 / 3)
    b = 4e-3 * (fn / 1e5) ** (1 / 3)
    with np.errstate(divide="ignore", invalid="ignore"):
        p0 = np.where(fn > 0, 1.5 * fn / (np.pi * a * b), 0.0)
    creep = -creep_scale * 2e-3 * ripple * (fn > 0)
    fx = 0.6 * FRICTION * fn
    stick_len = 0.6 + 0.1 * np.sin(2 * np.pi * x_c / WAVELENGTH)  # fraction of strip in stick

    xi, eta, d_xi, d_eta = _mesh(n_strips, per_strip)
    half = np.sqrt(1 - eta**2)
    shape = np.sqrt(np.clip(1 - xi**2 - eta**2, 0, None))
    pressure = p0[:, None] * shape[None, :]
    stick = (xi[None, :] > half[None, :] * (1 - 2 * stick_len[:, None])).astype(np.int8)
    frac = np.clip((half - xi)[None, :] / (2 * half[None, :] * stick_len[:, None]), 0, 1)
    traction_x = FRICTION * pressure * np.where(stick == 1, frac, 1.0)
    slip_x = np.where(stick == 1, 0.0, -0.01 * (1 - frac) - 1e-3) * (fn[:, None] > 0)
    wear_rate = 1e-9 * np.abs(traction_x * slip_x) / 1e6
    zeros = np.zeros_like(pressure)
    n_el = xi.size

    data = {
        "time": _var("step", time, "s", "time"),
        "x_c": _var("step", x_c, "m", "contact patch centre along the rail"),
        "normal_force": _var("step", fn, "N", "normal force"),
        "longitudinal_force": _var("step", fx, "N", "longitudinal force on the wheel"),
        "creepage_x": _var("step", creep, "1", "longitudinal creepage"),
        "creepage_y": _var("step", np.zeros(n_steps), "1", "lateral creepage"),
        "spin": _var("step", np.full(n_steps, 0.05), "1/m", "spin creepage"),
        "semi_axis_a": _var("step", a, "m", "contact semi-axis along the rail"),
        "semi_axis_b": _var("step", b, "m", "contact semi-axis across the rail"),
        "max_pressure": _var("step", p0, "Pa", "maximum contact pressure"),
        "contact_area": _var("step", np.pi * a * b * (fn > 0), "m2", "area in contact"),
        "stick_fraction": _var("step", stick.mean(axis=1) * (fn > 0), "1", "stick area fraction"),
        "xi": _var("element", xi, "1", "normalised element centre x/a"),
        "eta": _var("element", eta, "1", "normalised element centre y/b"),
        "d_xi": _var("element", d_xi, "1", "normalised element length along x"),
        "d_eta": _var("element", d_eta, "1", "normalised strip width"),
        "pressure": _var(("step", "element"), pressure, "Pa", "normal pressure"),
        "traction_x": _var(("step", "element"), traction_x, "Pa", "longitudinal traction"),
        "traction_y": _var(("step", "element"), zeros, "Pa", "lateral traction"),
        "slip_x": _var(("step", "element"), slip_x, "m/s", "longitudinal slip velocity"),
        "slip_y": _var(("step", "element"), zeros, "m/s", "lateral slip velocity"),
        "wear_rate": _var(("step", "element"), wear_rate, "m/s", "Archard wear rate"),
        "stick": _var(("step", "element"), stick, "1", "stick flag (1 stick, 0 slip)"),
    }
    if extras:
        data["newton_iterations"] = _var("step", 3 + (np.arange(n_steps) % 4), "1", "Newton iterations")
        data["in_contact"] = _var("step", in_contact, "1", "wheel in contact flag")
        data["mystery_future_variable"] = _var("step", np.zeros(n_steps), "1", "unknown to postprocess")
    coords = {
        "step": _var("step", np.arange(n_steps), "1", "time step index"),
        "element": _var("element", np.arange(n_el), "1", "contact element index"),
    }
    return xr.Dataset(data, coords=coords)


def write_rail(path: Path, prefix: str, n_pass: int, wear_scale: float, creep_scale: float,
               extras: bool, growth: bool) -> None:
    """One rail's groups ``rail``, ``passes`` and ``contact/pass_NNNNN`` under ``prefix``."""
    rail = rail_dataset(n_pass, wear_scale)
    rail.to_netcdf(path, engine="h5netcdf", group=f"{prefix}rail", mode="a")
    passes = passes_dataset(rail, extras or growth)
    if growth:
        passes = growth_variables(passes, wear_scale)
    passes.to_netcdf(path, engine="h5netcdf", group=f"{prefix}passes", mode="a")
    for p in rail["pass"].values:
        group = f"{prefix}contact/pass_{int(p):05d}"
        contact_dataset(int(p), creep_scale, extras).to_netcdf(path, engine="h5netcdf", group=group, mode="a")


#: The rail names of a two-rail synthetic file, and the second rail's scale of wear and creepage.
RAIL_NAMES = ("left rail", "right rail")
SECOND_SCALE = 1.7


def write_run(path: str | Path, *, contact_model: str = "fastsim", n_pass: int = 2,
              wear_scale: float = 1.0, creep_scale: float = 1.0, extras: bool = False,
              growth: bool = False, second_rail: bool = False) -> Path:
    """Write a synthetic run file; ``extras`` adds optional and unknown
    variables, ``growth`` a growth study's (band levels included);
    ``second_rail`` the group ``second_rail`` (the layout of the root's
    rail, passes and contact groups, SECOND_SCALE times the wear and
    creepage) and the root attribute ``rail_name``."""
    path = Path(path)
    attrs = {"config": CONFIG, "version": "0.1.0-synthetic",
             "title": "synthetic test run", "contact_model": contact_model}
    if second_rail:
        attrs["rail_name"] = RAIL_NAMES[0]
    xr.Dataset(attrs=attrs).to_netcdf(path, engine="h5netcdf", mode="w")
    write_rail(path, "", n_pass, wear_scale, creep_scale, extras, growth)
    if second_rail:
        xr.Dataset(attrs={"rail_name": RAIL_NAMES[1]}).to_netcdf(path, engine="h5netcdf", group="second_rail", mode="a")
        write_rail(path, "second_rail/", n_pass, SECOND_SCALE * wear_scale, SECOND_SCALE * creep_scale, extras, growth)
    return path
