#!/usr/bin/python3
"""Would balls with mass make a race pit's strikes grow faster with the ball's load, as the real
CWRU outer-race faults' do (docs/cwru_rig.md, "A load turning with the shaft")? A one-ball,
one-direction study, not the package's model.

One ball between the inner ring (the rotor share, 5 kg, held by the other balls' 1.5e7 N/m)
and the outer race, which holds a sharp-edged pit: a ball over it pivots on the nearer edge,
so the race's surface under the ball recedes by D (1 - 2|s| / w)^2, D = w^2 / 8 (2 / d - 1 / R_o)
(docs/model.md 9.6). The contact point runs over the pit at 1.76 m/s (the 6205 at 1797 rpm).
Either the ball is massless (its two Hertz contacts in series, the package's model) or it has
its mass (2.05 g) and its own equation of motion between the two contacts. Printed: the power
in 2-4 kHz of the force the outer race takes (this ball's contact and the others' change),
relative to a reference, for ball loads of 2-40 N and for the three CWRU pit widths.

    /usr/bin/python3 dev/ball_mass_study.py

Not executable and not installed: a development script.
"""
import numpy as np
from scipy.optimize import brentq

K_INNER, K_OUTER = 1.4e10, 1.3e10  # Hertz constants of the 6205's contacts, N/m^1.5
BALL_MASS_KG, RING_MASS_KG, OTHER_BALLS_N_PER_M = 2.05e-3, 5.0, 1.5e7
SPEED_M_S = 1.76
BALL_DIAMETER_M, OUTER_RACE_RADIUS_M = 7.94e-3, 23.5e-3


def hertz(k, deflection):
    return k * deflection ** 1.5 if deflection > 0.0 else 0.0


def outer_race_force(load_n, width_m, massless, duration_s=1.2e-3):
    """The outer race's force (N) every 0.2 us while the ball crosses the pit, and that step."""
    drop = width_m ** 2 / 8.0 * (2.0 / BALL_DIAMETER_M - 1.0 / OUTER_RACE_RADIUS_M)
    inner0, outer0 = (load_n / K_INNER) ** (2 / 3), (load_n / K_OUTER) ** (2 / 3)
    dt = 2e-7 if massless else 2e-8  # the ball on its contacts rings at ~20 kHz: small steps
    every = int(round(2e-7 / dt))
    ring = ball = ring_speed = ball_speed = 0.0  # outward displacements, m; speeds, m/s
    out = []
    for k in range(int(duration_s / dt)):
        s = -0.6e-3 + SPEED_M_S * k * dt
        x = 1.0 - 2.0 * abs(s) / width_m
        dip = drop * x * x if x > 0.0 else 0.0
        if massless:  # the ball where its two contact forces are equal
            gap = lambda u: hertz(K_INNER, inner0 + ring - u) - hertz(K_OUTER, outer0 + u - dip)
            low, high = dip - outer0, inner0 + ring
            ball = brentq(gap, low, high) if gap(low) * gap(high) < 0.0 else (low if gap(low) <= 0.0 else high)
        inner = hertz(K_INNER, inner0 + ring - ball)
        outer = inner if massless else hertz(K_OUTER, outer0 + ball - dip)
        if not massless:
            ball_speed += (inner - outer) / BALL_MASS_KG * dt
            ball += ball_speed * dt
        ring_speed += (load_n - inner - OTHER_BALLS_N_PER_M * ring) / RING_MASS_KG * dt
        ring += ring_speed * dt
        if k % every == 0:
            out.append(outer + OTHER_BALLS_N_PER_M * ring)
    return np.array(out), dt * every


def band_power(x, step_s, low_hz=2000.0, high_hz=4000.0):
    spectrum = np.fft.rfft((x - x.mean()) * np.hanning(x.size))
    f = np.fft.rfftfreq(x.size, step_s)
    return float(np.sum(np.abs(spectrum[(f >= low_hz) & (f < high_hz)]) ** 2))


def main():
    width_021 = 0.021 * 25.4e-3
    for massless in (True, False):
        power = {q: band_power(*outer_race_force(q, width_021, massless)) for q in (2.0, 5.0, 10.0, 20.0, 40.0)}
        print(('massless ball' if massless else 'ball of 2.05 g') + ', 0.021 in pit, 2-4 kHz against 10 N: '
              + ', '.join(f'{q:g} N {10 * np.log10(p / power[10.0]):+.1f} dB' for q, p in power.items()))
    reference = band_power(*outer_race_force(20.0, width_021, True))
    for size_in in (0.021, 0.014, 0.007):
        row = [f'{size_in} in at 20 N, 2-4 kHz against the massless 0.021 in:']
        for massless in (True, False):
            p = band_power(*outer_race_force(20.0, size_in * 25.4e-3, massless))
            row.append(f"{'massless' if massless else '2.05 g'} {10 * np.log10(p / reference):+.1f} dB")
        print(' '.join(row))


if __name__ == '__main__':
    main()
