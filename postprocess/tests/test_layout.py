"""The run file follows the layout contract (groups, dims, attributes, mesh order)."""

from __future__ import annotations

import h5py
import netCDF4
import numpy as np
import xarray as xr

from corrugation_post import io, schema


def _groups(path):
    return schema.expected_groups(path)


def test_groups_open_with_named_dims(run_file):
    groups = _groups(run_file)
    assert any(g.startswith("contact/pass_") for g in groups), "no contact/pass_NNNNN group"
    wanted_dims = {"rail": {"pass", "y", "x"}, "passes": {"pass"}}
    for group in groups:
        with xr.open_dataset(run_file, engine="h5netcdf", group=group) as ds:
            dims = set(map(str, ds.dims))
            assert not [d for d in dims if d.startswith("phony_dim")], (group, dims)
            own = group.removeprefix(io.SECOND_PREFIX)  # a two-rail file's second rail
            assert wanted_dims.get(own, {"step", "element"}) <= dims, (group, dims)


def test_required_variables_have_contract_dims(run_file):
    for group, required in _groups(run_file).items():
        with io.open_group(run_file, group) as ds:
            for name, dims in required.items():
                assert name in ds.variables, f"{group}: missing {name}"
                assert tuple(ds[name].dims) == dims, f"{group}/{name}: {ds[name].dims} != {dims}"


def test_every_variable_has_units_and_long_name(run_file):
    missing = []
    for group in _groups(run_file):
        with io.open_group(run_file, group) as ds:
            for name, var in ds.variables.items():
                missing += [f"{group}/{name}:{a}" for a in ("units", "long_name") if a not in var.attrs]
    assert not missing


def test_units_are_si(run_file):
    problems = []
    for group, required in _groups(run_file).items():
        with io.open_group(run_file, group) as ds:
            problems += [p for p in schema.check_dataset(ds, group, required) if "units" in p]
    assert not problems


def test_root_attributes_and_config(run_file):
    attrs = io.root_attrs(run_file)
    for name in schema.ROOT_ATTRS:
        assert name in attrs, name
        assert isinstance(attrs[name], str) and attrs[name], name
    config = io.parse_config(attrs["config"], run_file)
    assert 0 < io.friction_coefficient(config) < 1


def test_one_contact_group_per_stored_passage(run_file):
    assert io.stored_passes(run_file) == io.contact_passes(run_file)


def test_traffic_is_cumulative(run_file):
    for group in ("rail", "passes"):
        with io.open_group(run_file, group) as ds:
            assert np.all(np.diff(ds["traffic"].values) >= 0), group


def test_contact_mesh_order_and_stick_flags(run_file):
    for group in _groups(run_file):
        if group.startswith("contact/"):
            with io.open_group(run_file, group) as ds:
                assert schema.check_mesh(ds, group) == []
                assert ds["stick"].dtype == np.int8


def test_netcdf4_library_reads_the_file(run_file):
    """netCDF-4 compatibility: the netCDF-C library sees the groups and named dims."""
    with netCDF4.Dataset(run_file) as nc:
        rail = nc.groups["rail"]
        assert {"pass", "y", "x"} <= set(rail.dimensions)
        assert rail.variables["wear"].dimensions == ("pass", "y", "x")
        first = f"pass_{io.contact_passes(run_file)[0]:05d}"
        assert nc.groups["contact"].groups[first].variables["traction_x"].dimensions == ("step", "element")


def test_dimension_scales_are_attached(run_file):
    """Every dataset of rank >= 1 has a dimension scale on each axis (h5py view)."""
    unattached = []

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset) and obj.ndim and not obj.is_scale:
            unattached.extend(f"{name}[{i}]" for i, d in enumerate(obj.dims) if len(d) == 0)

    with h5py.File(run_file, "r") as f:
        f.visititems(visit)
    assert not unattached


def test_check_command_reports_no_problem(run_file):
    assert schema.check_file(run_file) == []
