"""Unit conversion through the ``units`` attribute, and the depth unit of
the wear figures."""

import numpy as np
import pytest
import xarray as xr

from corrugation_post.units import depth_unit, values_in


def _depth(values):
    return xr.DataArray(np.asarray(values, dtype=float), dims="x", attrs={"units": "m"})


def test_values_in_converts_through_the_attribute():
    d = _depth([1e-9, 2e-6])
    assert values_in(d, "nm") == pytest.approx([1.0, 2000.0])
    assert values_in(d, "um") == pytest.approx([1e-3, 2.0])
    with pytest.raises(ValueError, match="cannot convert"):
        values_in(d, "kN")


def test_one_passage_of_wear_is_drawn_in_nanometres():
    # 0.47 nm, one passage of paper_normal_30mm: in µm it would read 0.00047.
    assert depth_unit(_depth([0.0, 4.7e-10])) == ("nm", "nm")
    # A grown corrugation, 0.2 µm and more: in µm.
    assert depth_unit(_depth([0.0, -2e-7])) == ("um", "µm")
