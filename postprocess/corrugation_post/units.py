"""Unit conversion driven by each variable's ``units`` attribute.

Run files store SI units; plots use mm, um (micrometres) and kN.  Converting
through the attribute, rather than assuming SI, makes a unit mistake in the
writer fail loudly instead of producing a plot off by 1000.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from .io import as_str

_ALIASES = {
    "meter": "m", "meters": "m", "metre": "m", "metres": "m",
    "millimetre": "mm", "millimeter": "mm",
    "micrometre": "um", "micrometer": "um", "µm": "um", "μm": "um",
    "nanometre": "nm", "nanometer": "nm",
    "newton": "N", "newtons": "N",
    "second": "s", "seconds": "s",
    "": "1", "-": "1", "dimensionless": "1",
}
# Metres per unit, newtons per unit, seconds per unit, 1 per unit.
_SCALE = {
    "m": ("length", 1.0), "mm": ("length", 1e-3), "um": ("length", 1e-6), "nm": ("length", 1e-9),
    "N": ("force", 1.0), "kN": ("force", 1e3),
    "s": ("time", 1.0), "ms": ("time", 1e-3),
    "1": ("ratio", 1.0),
}


def normalise(unit: str) -> str:
    """Canonical spelling of a unit string."""
    unit = str(as_str(unit)).strip()
    return _ALIASES.get(unit.lower(), _ALIASES.get(unit, unit))


def factor(from_unit: str, to_unit: str) -> float:
    """Multiplier converting values in ``from_unit`` to ``to_unit``."""
    src, dst = normalise(from_unit), normalise(to_unit)
    if src == dst:
        return 1.0
    try:
        (kind_s, s), (kind_d, d) = _SCALE[src], _SCALE[dst]
    except KeyError:
        raise ValueError(f"cannot convert {from_unit!r} to {to_unit!r}") from None
    if kind_s != kind_d:
        raise ValueError(f"cannot convert {from_unit!r} ({kind_s}) to {to_unit!r} ({kind_d})")
    return s / d


def values_in(da: xr.DataArray, to_unit: str) -> np.ndarray:
    """Values of ``da`` converted from its ``units`` attribute to ``to_unit``."""
    if "units" not in da.attrs:
        raise ValueError(f"variable {da.name!r} has no 'units' attribute")
    try:
        k = factor(da.attrs["units"], to_unit)
    except ValueError as err:
        raise ValueError(f"variable {da.name!r}: {err}") from None
    return np.asarray(da.values, dtype=float) * k


def depth_unit(da: xr.DataArray) -> tuple[str, str]:
    """The unit to draw a small length (a wear depth) in, and its label: nm
    below 0.1 µm (one passage's wear is a fraction of a nanometre, whose
    µm values would read like metres), µm otherwise."""
    largest = float(np.nanmax(np.abs(values_in(da, "m")))) if da.size else 0.0
    return ("nm", "nm") if largest < 1e-7 else ("um", "µm")
