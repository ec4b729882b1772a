"""Reading corrugation run files (HDF5, netCDF-4 compatible).

The layout (groups ``rail``, ``passes`` and ``contact/pass_NNNNN``) is described
in ``schema.py`` and in the book (docs/src/reference/run-file.md).  Structure (which groups exist, root
attributes) is read with h5py; data are opened as xarray Datasets with the
h5netcdf engine, so dimension names come from the HDF5 dimension scales.

A file of both rails of a wheelset keeps the first rail's groups at the root
(root attribute ``rail_name``) and the second rail's in group ``second_rail``
(attribute ``rail_name``), with the same layout: ``rails`` lists them, and a
``Run`` reads one rail's groups (``Run.rails``).

Note that ``pass`` is a Python keyword: use ``ds["pass"]`` and
``da.sel({"pass": n})`` rather than attribute access.
"""

from __future__ import annotations

import csv
import re
import tomllib
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import h5py
import numpy as np
import xarray as xr

RAIL = "rail"
PASSES = "passes"
CONTACT = "contact"
SECOND_RAIL = "second_rail"
#: Group prefix of the second rail's groups, and the suffix of its figures' file names.
SECOND_PREFIX, SECOND_SUFFIX = f"{SECOND_RAIL}/", f"_{SECOND_RAIL}"
_CONTACT_RE = re.compile(r"^pass_(\d{5,})$")


class RunFileError(Exception):
    """A run file is missing, unreadable or does not follow the layout."""


def contact_group(pass_index: int) -> str:
    """Group path of the contact history of stored passage ``pass_index``."""
    return f"{CONTACT}/pass_{int(pass_index):05d}"


def as_str(value: Any) -> Any:
    """Decode HDF5 string attributes (bytes, 0-d or 1-element arrays) to str."""
    if isinstance(value, np.ndarray) and value.size == 1:
        value = value.reshape(()).item()
    if isinstance(value, (bytes, np.bytes_)):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, np.str_):
        return str(value)
    return value


def check_run_file(path: str | Path) -> Path:
    """Return ``path`` as a Path if it is an HDF5 file with a ``rail`` group.

    Raises RunFileError with a message naming the file otherwise.
    """
    path = Path(path)
    if not path.exists():
        raise RunFileError(f"{path}: no such file")
    if not path.is_file():
        raise RunFileError(f"{path}: not a regular file")
    if not h5py.is_hdf5(path):
        raise RunFileError(f"{path}: not an HDF5 file (is this a corrugation run file?)")
    try:
        with h5py.File(path, "r") as f:
            has_rail = isinstance(f.get(RAIL), h5py.Group)
            kind = ("a `corrugation track` file (receptances): `corrugation-post track` draws it"
                    if isinstance(f.get("track"), h5py.Group)
                    else "a collected sweep: `corrugation-post sweep` maps it" if "sweep_spec" in f.attrs
                    else None)
    except OSError as err:  # truncated file, still being written, ...
        raise RunFileError(f"{path}: cannot be opened: {err}") from err
    if kind is not None:
        raise RunFileError(f"{path}: {kind}; not a run file")
    if not has_rail:
        raise RunFileError(
            f"{path}: no '{RAIL}' group; not a corrugation run file, "
            "or the run stopped before writing its results"
        )
    return path


def open_group(path: str | Path, group: str | None) -> xr.Dataset:
    """Open one group lazily as an xarray Dataset (use it as a context manager).

    Time-like units ("s") are left as plain floats.
    """
    try:
        return xr.open_dataset(
            path, engine="h5netcdf", group=group, decode_times=False, decode_timedelta=False
        )
    except (OSError, KeyError, ValueError) as err:
        raise RunFileError(f"{path}: cannot open group {group!r}: {err}") from err


def root_attrs(path: str | Path) -> dict[str, Any]:
    """Root attributes (``config``, ``version``, ``title``, ``contact_model``...)."""
    with h5py.File(path, "r") as f:
        return {k: as_str(v) for k, v in f.attrs.items()}


def parse_config(text: str, path: str | Path = "<config>") -> dict[str, Any]:
    """Parse the resolved TOML configuration text stored in the run file."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise RunFileError(f"{path}: root attribute 'config' is not valid TOML: {err}") from err


def friction_coefficient(config: dict[str, Any], path: str | Path = "<config>") -> float:
    """``material.friction_coefficient`` from a parsed config."""
    try:
        return float(config["material"]["friction_coefficient"])
    except (KeyError, TypeError, ValueError) as err:
        raise RunFileError(
            f"{path}: config has no numeric material.friction_coefficient"
        ) from err


@dataclass(frozen=True)
class RailGroups:
    """One rail of a run file: its name and the prefix of its groups."""

    name: str  # the ``rail_name`` attribute; "rail" in a one-rail file
    prefix: str  # "" (the root's groups) or SECOND_PREFIX


def rails(path: str | Path) -> list[RailGroups]:
    """The rails of a run file: the root's, and the second rail's when the
    file has a ``second_rail`` group."""
    with h5py.File(path, "r") as f:
        found = [RailGroups(str(as_str(f.attrs.get("rail_name", "rail"))), "")]
        second = f.get(SECOND_RAIL)
        if isinstance(second, h5py.Group):
            found.append(RailGroups(str(as_str(second.attrs.get("rail_name", "second rail"))), SECOND_PREFIX))
    return found


def stored_passes(path: str | Path, prefix: str = "") -> list[int]:
    """Stored passage indices: values of the ``rail`` group's ``pass`` coordinate."""
    group = prefix + RAIL
    with h5py.File(path, "r") as f:
        if group not in f or "pass" not in f[group]:
            raise RunFileError(f"{path}: group '{group}' has no 'pass' coordinate")
        return [int(p) for p in np.asarray(f[group]["pass"][()]).ravel()]


def contact_passes(path: str | Path, prefix: str = "") -> list[int]:
    """Passage indices that have a ``contact/pass_NNNNN`` group, sorted."""
    with h5py.File(path, "r") as f:
        grp = f.get(prefix + CONTACT)
        if not isinstance(grp, h5py.Group):
            return []
        found = (_CONTACT_RE.match(name) for name in grp)
        return sorted(int(m.group(1)) for m in found if m)


@dataclass
class Run:
    """A run file: its path, root attributes and parsed configuration, and
    the rail whose groups it reads (the root's unless ``Run.rails`` chose
    another)."""

    path: Path
    attrs: dict[str, Any] = field(repr=False)
    config: dict[str, Any] = field(repr=False)
    rail_groups: list[RailGroups] = field(repr=False, default_factory=lambda: [RailGroups("rail", "")])
    prefix: str = ""

    @classmethod
    def open(cls, path: str | Path) -> "Run":
        path = check_run_file(path)
        attrs = root_attrs(path)
        config = parse_config(str(attrs.get("config", "")), path)
        return cls(path=path, attrs=attrs, config=config, rail_groups=rails(path))

    def rails(self) -> list["Run"]:
        """One Run per rail of the file (one for a one-rail file)."""
        return [replace(self, prefix=r.prefix) for r in self.rail_groups]

    @property
    def two_rails(self) -> bool:
        return len(self.rail_groups) > 1

    @property
    def rail_name(self) -> str:
        """The rail's name in a two-rail file; "" in a one-rail file, whose
        figures and tables name no rail."""
        if not self.two_rails:
            return ""
        return next(r.name for r in self.rail_groups if r.prefix == self.prefix)

    @property
    def suffix(self) -> str:
        """What this rail's own figures add to their file names ("" or "_second_rail")."""
        return SECOND_SUFFIX if self.prefix else ""

    @property
    def contact_model(self) -> str:
        return str(self.attrs.get("contact_model", "unknown contact model"))

    @property
    def friction_coefficient(self) -> float:
        return friction_coefficient(self.config, self.path)

    def passes(self) -> list[int]:
        return stored_passes(self.path, self.prefix)

    def contact_passes(self) -> list[int]:
        return contact_passes(self.path, self.prefix)

    def resolve_pass(self, number: int | None) -> int:
        """The stored index (the ``pass`` coordinate, from 0) of passage
        ``number`` as the terminal counts passages (from 1), or of the last
        stored passage; error if not stored."""
        available = self.passes()
        if not available:
            raise RunFileError(f"{self.path}: no stored passages in group '{self.prefix}{RAIL}'")
        if number is None:
            return available[-1]
        if number - 1 not in available:
            raise RunFileError(
                f"{self.path}: passage {number} is not stored; stored passages (counted from 1): "
                f"{_short([p + 1 for p in available])}"
            )
        return number - 1

    def rail(self) -> xr.Dataset:
        return open_group(self.path, self.prefix + RAIL)

    def pass_table(self) -> xr.Dataset:
        return open_group(self.path, self.prefix + PASSES)

    def contact(self, pass_index: int) -> xr.Dataset:
        group = self.prefix + contact_group(pass_index)
        if pass_index not in self.contact_passes():
            raise RunFileError(
                f"{self.path}: no group '{group}'; "
                f"contact histories stored for passages: {_short(self.contact_passes())}"
            )
        return open_group(self.path, group)


def _short(values: list[int], keep: int = 8) -> str:
    if not values:
        return "none"
    if len(values) <= keep:
        return ", ".join(map(str, values))
    head = ", ".join(map(str, values[: keep // 2]))
    tail = ", ".join(map(str, values[-keep // 2 :]))
    return f"{head}, ..., {tail} ({len(values)} in all)"


def write_csv(path: str | Path, columns, rows) -> Path:
    """Writes ``rows`` (dicts) with the header ``columns`` to ``path``."""
    path = Path(path)
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(columns))
        writer.writeheader()
        writer.writerows(rows)
    return path


def read_csv(path: str | Path) -> list[dict]:
    """The rows of a CSV file with a header, as dicts."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))
