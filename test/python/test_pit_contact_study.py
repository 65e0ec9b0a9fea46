"""dev/pit_contact_study.py, the ball's contact over a pit solved on the elastic half-space: the
solver against Hertz's closed forms, for a sphere on a flat and for the 6205's elliptical contact
at the outer race (Johnson, Contact Mechanics, 1985, section 4.2); a hole carries nothing and lets
the ball sink, a rim round it lifts the ball."""
import math
import sys

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

from conftest import SOURCE

sys.path.insert(0, str(SOURCE / 'dev'))
import pit_contact_study as study  # noqa: E402


def test_a_sphere_on_a_flat_takes_hertz_approach():
    approach, exact = study.hertz_sphere_check()
    # 40 cells per contact radius: the discretisation's error is ~1e-4 (measured -3e-5).
    assert approach == pytest.approx(exact, rel=0.005)


def test_the_6205_outer_race_contact_takes_hertz_elliptical_approach_and_width():
    load = 24.0
    hs = study.HalfSpace(0.2e-3, 0.6e-3, 4e-6, 10e-6)
    pressure, approach = hs.solve(study.race_gap(hs, 'outer'), load, np.ones((hs.nx, hs.ny), dtype=bool))
    # Hertz: gap A y^2 + B x^2 (y across the track, the ellipse's long axis a), m = e^2 = 1 - b^2/a^2:
    # B / A = ((a/b)^2 E - K) / (K - E), A = 3 P (K - E) / (2 pi E* a^3 e^2), approach p0 b K / E*.
    short_curvature, long_curvature = (0.5 * c for c in study.CURVATURES['outer'])

    def curvature_ratio_error(m):
        return (ellipe(m) / (1 - m) - ellipk(m)) / (ellipk(m) - ellipe(m)) - short_curvature / long_curvature

    m = brentq(curvature_ratio_error, 1e-6, 1 - 1e-9)
    a = (3 * load * (ellipk(m) - ellipe(m)) / (2 * math.pi * study.E_STAR * long_curvature * m)) ** (1 / 3)
    b = a * math.sqrt(1 - m)
    exact = 3 * load / (2 * math.pi * a * b) * b * ellipk(m) / study.E_STAR
    assert approach == pytest.approx(exact, rel=0.005)
    # The loaded cells reach the ellipse's long semi-axis to within a cell (10 um of ~310).
    half_width = np.abs(hs.grid_y[pressure > 0]).max() + 0.5 * hs.dy
    assert half_width == pytest.approx(a, rel=hs.dy / a)


def test_a_hole_carries_nothing_and_lets_the_ball_sink_a_rim_lifts_it():
    hs = study.HalfSpace(0.2e-3, 0.6e-3, 4e-6, 10e-6)
    gap = study.race_gap(hs, 'outer')
    intact = study.intact_approach(hs, gap, 24.0)
    width = 0.014 * study.INCH
    _, outside = study.pit_surface(hs, 0.0, width, 0.0, 1e-4)
    pressure, holed = hs.solve(gap, 24.0, outside)
    assert not pressure[~outside].any()
    # Less surface to carry the same load: the ball sinks.
    assert holed > intact
    height, outside = study.pit_surface(hs, 0.0, width, 1e-6, 1e-4)
    _, rimmed = hs.solve(gap - height, 24.0, outside)
    assert rimmed < holed
