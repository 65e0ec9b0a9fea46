"""dev/pit_contact_study.py, the ball's contact over a pit solved on the elastic half-space: the
solver against Hertz's closed forms, for a sphere on a flat and for the 6205's elliptical contact
at the outer race (Johnson, Contact Mechanics, 1985, section 4.2)."""
import math
import sys

import numpy as np
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

from conftest import SOURCE

sys.path.insert(0, str(SOURCE / 'dev'))
import pit_contact_study as study  # noqa: E402


def test_a_sphere_on_a_flat_takes_hertz_approach():
    approach, exact = study.hertz_sphere_check()
    # 40 cells per contact radius: the discretisation's error is ~1e-4 (measured -3e-5).
    assert approach == _within(exact, 0.005)


def test_the_6205_outer_race_contact_takes_hertz_elliptical_approach_and_width():
    load = 24.0
    hs = study.HalfSpace(0.2e-3, 0.6e-3, 4e-6, 10e-6)
    x, y = np.meshgrid(hs.x, hs.y, indexing='ij')
    pressure, approach = hs.solve(x * x / (2 * study.R_X) + y * y / (2 * study.R_Y), load,
                                  np.ones_like(x, dtype=bool))
    # Hertz: gap A y^2 + B x^2 (y across the track, the ellipse's long axis a), m = e^2 = 1 - b^2/a^2:
    # B / A = ((a/b)^2 E - K) / (K - E), A = 3 P (K - E) / (2 pi E* a^3 e^2), approach p0 b K / E*.
    long_curvature, short_curvature = 0.5 / study.R_Y, 0.5 / study.R_X
    ratio = lambda m: (ellipe(m) / (1 - m) - ellipk(m)) / (ellipk(m) - ellipe(m)) - short_curvature / long_curvature
    m = brentq(ratio, 1e-6, 1 - 1e-9)
    a = (3 * load * (ellipk(m) - ellipe(m)) / (2 * math.pi * study.E_STAR * long_curvature * m)) ** (1 / 3)
    b = a * math.sqrt(1 - m)
    exact = 3 * load / (2 * math.pi * a * b) * b * ellipk(m) / study.E_STAR
    assert approach == _within(exact, 0.005)
    # The loaded cells reach the ellipse's long semi-axis to within a cell (10 um of ~310).
    half_width = np.abs(y[pressure > 0]).max() + 0.5 * hs.dy
    assert half_width == _within(a, hs.dy / a)
    # The pressure's total is the load.
    assert pressure.sum() * hs.dx * hs.dy == _within(load, 1e-9)


def _within(value, relative):
    import pytest
    return pytest.approx(value, rel=relative)
