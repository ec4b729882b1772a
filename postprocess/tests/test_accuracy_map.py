"""The Richardson reference of the accuracy map: the observed order and the
extrapolation recover a synthetic mesh sequence w(n) = w_inf + c n^-p."""

import numpy as np
import pytest

from corrugation_post.accuracy_map import extrapolate, observed_order
from corrugation_post.io import RunFileError


@pytest.mark.parametrize("p", [0.42, 0.93, 1.0, 2.0])
def test_observed_order_recovers_the_exponent(p):
    n = (14, 20, 28)
    w_inf, c = np.array([1.0, 2.0, 3.0]), np.array([0.5, -0.2, 0.1])
    w = [w_inf + c * k ** -p for k in n]
    got = observed_order(n, float(np.linalg.norm(w[1] - w[0])), float(np.linalg.norm(w[2] - w[1])))
    assert abs(got - p) < 1e-9
    ref, p_ref = extrapolate(n, *w)
    assert p_ref == got
    assert np.allclose(ref, w_inf, rtol=0, atol=1e-9)


def test_a_diverging_sequence_is_refused():
    with pytest.raises(RunFileError, match="not that of a converging sequence"):
        observed_order((14, 20, 28), 1.0, 2.0)
