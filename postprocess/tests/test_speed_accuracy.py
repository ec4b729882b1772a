"""Pure parts of the speed-accuracy harness: the Pareto front and the first
harmonic of a wear profile."""

from __future__ import annotations

import numpy as np

from corrugation_post.speed_accuracy import _harmonic, pareto


def test_pareto_front_keeps_only_unbeaten_points():
    points = [(1.0, 0.5), (2.0, 0.2), (3.0, 0.3), (0.5, 0.9), (2.0, 0.25)]
    assert pareto(points) == [0, 1, 3]


def test_first_harmonic_amplitude_and_phase():
    x = np.arange(0.0, 0.06 + 1e-12, 1e-4)
    w = 2e-9 + 3e-10 * np.sin(2 * np.pi * x / 0.03 + 0.4)
    h = _harmonic(x, w, 0.03)
    assert abs(abs(h) - 3e-10) < 1e-14
    # sin(t + 0.4) = cos(t + 0.4 - pi/2): phase 0.4 - pi/2
    assert abs(np.angle(h) - (0.4 - np.pi / 2)) < 1e-6
