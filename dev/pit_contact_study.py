#!/usr/bin/python3
"""What does a ball feel over a round EDM pit with its recast rim? The contact solved on the
elastic half-space, not the package's model (docs/cwru_rig.md, "Round pits and their recast rim").

The package takes a pit as an offset of the ball's approach, dip(x) (docs/model.md 9.6): a Hertz
contact over a surface whose height changes under its centre, the same for every load. Here the
contact itself is solved: a 6205 ball (d = 7.94 mm) against the outer race (groove f = 0.53,
race radius (dm + d) / 2 along the track, curving towards the ball) or the inner race (f = 0.52,
(dm - d) / 2, curving away), steel on steel (E = 208 GPa, nu = 0.3), the gap between the two
unloaded surfaces h0 = x^2 / (2 R_x) + y^2 / (2 R_y), x along the track. The race
holds a round hole w across (no contact inside it; 0.28 mm deep, far deeper than any approach)
and round it the rim of docs/model.md 9.6: H sin^2(pi (rho - w / 2) / b) for w / 2 <= rho <
w / 2 + b, rho the distance from the pit's centre. For a load Q and the pit's centre at a
distance s along the track from the contact's centre, the pressure that carries Q and the rigid
approach delta(Q, s) it takes are found by the conjugate-gradient method of Polonsky and Keer
(Wear 231, 1999), the surface displacements by the discrete convolution of uniform pressure on
rectangles (Johnson, Contact Mechanics, 1985, eq. 3.25) through zero-padded FFTs (Liu, Wang and
Liu, Wear 243, 2000). The pit's equivalent dip is delta(Q, s) - delta(Q, far): what the package's
dip(x) stands for, so the two are compared directly; a dip that grows with Q is a strike that
follows the ball's load.

    /usr/bin/python3 dev/pit_contact_study.py [--out DIR]

Printed: the solver against Hertz's closed form for a sphere on a flat; per race, pit width, rim
and load, the dip over the pit's centre and at the rim's crest, and the strike: the change of the
contact's force, K (delta0 - dip)^1.5 - Q at the approach delta0 that carries Q without the pit
(this contact alone, its Hertz constant K = Q / delta0^1.5), while the pit passes at 1.76 m/s
(the 6205's races at 1797 rpm), its largest value and its energy in 1-2 and 2-4 kHz; each
for the package's dip beside. With --out, the profiles as a CSV and a PNG.
Not executable and not installed: a development script.
"""
import argparse
import math
import pathlib

import numpy as np

E_PA, NU = 208e9, 0.3
E_STAR = E_PA / (2.0 * (1.0 - NU * NU))  # two steel bodies (Johnson's E*)
BALL_D, PITCH_D = 7.94004e-3, 39.0398e-3
# The ball's and the race's curvatures summed (1/m), along the track and across it: the outer race
# curves towards the ball along the track, the inner race away; across, each groove (f = 0.53
# outer, 0.52 inner) nearly conforms.
CURVATURES = {'outer': (2.0 / BALL_D - 2.0 / (PITCH_D + BALL_D), 2.0 / BALL_D - 1.0 / (0.53 * BALL_D)),
              'inner': (2.0 / BALL_D + 2.0 / (PITCH_D - BALL_D), 2.0 / BALL_D - 1.0 / (0.52 * BALL_D))}
INCH = 25.4e-3
SPEED_M_S = 1.76  # the contacts' speed over either race at 1797 rpm


def influence(nx, ny, dx, dy):
    """Surface displacement (m per Pa, both bodies) at every cell centre of a (2nx, 2ny) grid in
    FFT order, due to uniform pressure on the cell at the origin (Johnson eq. 3.25)."""
    ix = np.arange(2 * nx)
    iy = np.arange(2 * ny)
    ix = np.where(ix < nx, ix, ix - 2 * nx) * dx
    iy = np.where(iy < ny, iy, iy - 2 * ny) * dy
    x, y = np.meshgrid(ix, iy, indexing='ij')
    a, b = 0.5 * dx, 0.5 * dy

    def f(u, v):  # u ln(v + sqrt(u^2 + v^2)) + v ln(u + sqrt(u^2 + v^2))
        r = np.hypot(u, v)
        return u * np.log(v + r) + v * np.log(u + r)

    c = f(x + a, y + b) - f(x + a, y - b) - f(x - a, y + b) + f(x - a, y - b)
    return c / (math.pi * E_STAR)


class HalfSpace:
    """The contact on an nx x ny grid of cells dx x dy centred on the origin."""

    def __init__(self, half_x, half_y, dx, dy):
        self.nx, self.ny = int(round(2 * half_x / dx)), int(round(2 * half_y / dy))
        self.dx, self.dy = dx, dy
        self.x = (np.arange(self.nx) - 0.5 * (self.nx - 1)) * dx
        self.y = (np.arange(self.ny) - 0.5 * (self.ny - 1)) * dy
        self.grid_x, self.grid_y = np.meshgrid(self.x, self.y, indexing='ij')  # each cell's centre
        self.kernel = np.fft.rfft2(influence(self.nx, self.ny, dx, dy))

    def displacement(self, p):
        padded = np.zeros((2 * self.nx, 2 * self.ny))
        padded[:self.nx, :self.ny] = p
        return np.fft.irfft2(np.fft.rfft2(padded) * self.kernel, padded.shape)[:self.nx, :self.ny]

    def solve(self, gap0, load_n, allowed, tol=1e-7, iterations=3000):
        """Pressure (Pa) carrying load_n over the cells where allowed, and the rigid approach (m):
        the gap gap0 + u - approach is >= 0 everywhere and 0 where p > 0 (Polonsky and Keer's
        conjugate gradients)."""
        area = self.dx * self.dy
        p = np.where(allowed, load_n / (area * allowed.sum()), 0.0)
        t = np.zeros_like(p)
        g_old, restart = 1.0, True
        for _ in range(iterations):
            g = gap0 + self.displacement(p)
            contact = p > 0.0
            mean = g[contact].mean()
            g = g - mean
            gg = float(np.sum(g[contact] ** 2))
            t = np.where(contact, g + (0.0 if restart else gg / g_old) * t, 0.0)
            g_old = gg
            r = self.displacement(t)
            r = r - r[contact].mean()
            tau = float(np.sum(g[contact] * t[contact]) / np.sum(r[contact] * t[contact]))
            p_old = p
            p = np.maximum(np.where(contact, p - tau * t, 0.0), 0.0)
            overlap = (p == 0.0) & (g < 0.0) & allowed
            restart = bool(overlap.any())
            if restart:
                p[overlap] -= tau * g[overlap]
            p *= load_n / (area * p.sum())
            if np.sum(np.abs(p - p_old)) * area / load_n < tol:
                break
        g = gap0 + self.displacement(p)
        return p, float(g[p > 0.0].mean())


def hertz_sphere_check():
    """Sphere (R = 10 mm) on a flat under 50 N: approach against a^2 / R, Q = 4/3 E* sqrt(R) d^1.5."""
    radius, load = 10e-3, 50.0
    exact = (3.0 * load / (4.0 * E_STAR * math.sqrt(radius))) ** (2.0 / 3.0)
    a = math.sqrt(exact * radius)
    hs = HalfSpace(1.5 * a, 1.5 * a, a / 40.0, a / 40.0)
    gap = (hs.grid_x ** 2 + hs.grid_y ** 2) / (2.0 * radius)
    _, approach = hs.solve(gap, load, np.ones_like(gap, dtype=bool))
    return approach, exact


def package_dip(s, w, rim_h, rim_b, race):
    """docs/model.md 9.6's dip (m, positive: a drop) of a round, sharp-edged pit in the race, the
    contact's centre s from the pit's centre along the track."""
    along_sum, across_sum = CURVATURES[race]

    def across(span):  # the gap across the track over a span: the ball rests on its ends
        return span * span / 8.0 * across_sum

    along = w * w / 8.0 * along_sum
    half, crest = 0.5 * w, 0.5 * (w + rim_b)
    a = abs(s)
    pit = min(along * (1.0 - a / half) ** 2, across(w + rim_b) if rim_h > 0 else across(w)) if a < half else 0.0
    if rim_h > 0 and a < crest:
        return min(across(2.0 * math.sqrt(crest * crest - a * a)) - rim_h, pit)
    if rim_h > 0 and a < half + rim_b:
        return -rim_h * math.sin(math.pi * (a - half) / rim_b) ** 2
    return pit


def strike(positions, dips, load, approach):
    """The contact's force change (N) as the pit passes at SPEED_M_S at the approach that carries
    load without it: its largest value and its energy (N^2 s) in 1-2 and 2-4 kHz."""
    s = np.concatenate([-positions[:0:-1], positions])
    d = np.concatenate([dips[:0:-1], dips])
    t = np.linspace(s[0], s[-1], 4096) / SPEED_M_S
    force = load * (np.maximum(approach - np.interp(t * SPEED_M_S, s, d), 0.0) / approach) ** 1.5 - load
    n, dt = 1 << 20, t[1] - t[0]
    spectrum = np.abs(np.fft.rfft(force, n)) * dt
    f = np.fft.rfftfreq(n, dt)
    energy = lambda low, high: 2.0 * np.sum(spectrum[(f >= low) & (f < high)] ** 2) * f[1]
    return float(np.abs(force).max()), energy(1000.0, 2000.0), energy(2000.0, 4000.0)


def pit_surface(hs, s, w, rim_h, rim_b):
    """The race's height (m, towards the ball) on each cell and the cells outside the hole, the
    pit's centre at (s, 0) from the contact's centre."""
    rho = np.hypot(hs.grid_x - s, hs.grid_y)
    on_rim = (rho >= 0.5 * w) & (rho < 0.5 * w + rim_b)
    height = np.where(on_rim, rim_h * np.sin(math.pi * (rho - 0.5 * w) / rim_b) ** 2, 0.0)
    return height, rho >= 0.5 * w


def race_gap(hs, race):
    """The gap (m) between the unloaded ball and the intact race on each cell."""
    along_sum, across_sum = CURVATURES[race]
    return 0.5 * (hs.grid_x ** 2 * along_sum + hs.grid_y ** 2 * across_sum)


def intact_approach(hs, gap, load):
    """The approach (m) that carries load on the intact race."""
    return hs.solve(gap, load, np.ones_like(gap, dtype=bool))[1]


def profile(hs, gap, intact, w, rim_h, rim_b, load, positions):
    """The pit's equivalent dip (m) at each position of its centre: the approach over it less the
    intact one."""
    dips = []
    for s in positions:
        height, allowed = pit_surface(hs, s, w, rim_h, rim_b)
        dips.append(hs.solve(gap - height, load, allowed)[1] - intact)
    return np.array(dips)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--out', type=pathlib.Path, help='directory for the profiles (CSV, PNG)')
    parser.add_argument('--loads', default='8,15,30', help='ball loads, N, comma-separated')
    parser.add_argument('--rims', default='0,1', help='rim heights, um, comma-separated')
    parser.add_argument('--rim-width-um', type=float, default=100.0)
    parser.add_argument('--step-um', type=float, default=10.0, help='pit positions every step')
    parser.add_argument('--races', default='outer,inner', help='the pit in the outer race, the inner, or both')
    args = parser.parse_args(argv)
    approach, exact = hertz_sphere_check()
    print(f'solver check, sphere on a flat: approach {approach * 1e6:.4f} um, Hertz {exact * 1e6:.4f} um '
          f'({100 * (approach / exact - 1):+.2f} %)')
    hs = HalfSpace(0.2e-3, 0.6e-3, 4e-6, 10e-6)
    loads = [float(v) for v in args.loads.split(',')]
    rims = [float(v) * 1e-6 for v in args.rims.split(',')]
    rim_b = args.rim_width_um * 1e-6
    races = args.races.split(',')
    rows = []
    print('| race | pit (in) | rim (um) | load (N) | dip over the centre (um, + drop) | at the crest '
          '| strike, largest (N) | strike energy 2-4 kHz (N^2 us) | its 1-2 over 2-4 kHz |')
    print('|---' * 9 + '|')
    print('| | | | | half-space / package | | | | |')
    for race in races:
        gap = race_gap(hs, race)
        intact_by_load = {load: intact_approach(hs, gap, load) for load in loads}  # one per load, not per pit
        for inches in (0.007, 0.014, 0.021):
            w = inches * INCH
            positions = np.arange(0.0, 0.5 * w + rim_b + 0.15e-3, args.step_um * 1e-6)
            crest = np.argmin(np.abs(positions - (0.5 * w + 0.5 * rim_b)))
            for rim_h in rims:
                model = np.array([package_dip(s, w, rim_h, rim_b, race) for s in positions])
                for load in loads:
                    intact = intact_by_load[load]
                    dips = profile(hs, gap, intact, w, rim_h, rim_b, load, positions)
                    rows += [(race, inches, rim_h * 1e6, load, s * 1e3, d * 1e6, m * 1e6, intact * 1e6)
                             for s, d, m in zip(positions, dips, model)]
                    ours, theirs = strike(positions, dips, load, intact), strike(positions, model, load, intact)
                    print(f'| {race} | {inches:.3f} | {rim_h * 1e6:.1f} | {load:.0f} | {dips[0] * 1e6:+.2f} / '
                          f'{model[0] * 1e6:+.2f} | {dips[crest] * 1e6:+.2f} / {model[crest] * 1e6:+.2f} | '
                          f'{ours[0]:.1f} / {theirs[0]:.1f} | {ours[2] * 1e6:.0f} / {theirs[2] * 1e6:.0f} | '
                          f'{ours[1] / ours[2]:.2f} / {theirs[1] / theirs[2]:.2f} |', flush=True)
    if args.out:
        args.out.mkdir(parents=True, exist_ok=True)
        with open(args.out / 'pit_contact_profiles.csv', 'w') as f:
            f.write('race,pit_in,rim_um,load_N,position_mm,dip_um,package_dip_um,intact_approach_um\n')
            f.writelines(','.join([row[0]] + [f'{v:.6g}' for v in row[1:]]) + '\n' for row in rows)
        plot(rows, races, loads, rims, args.out / 'pit_contact_profiles.png')


def plot(rows, races, loads, rims, path):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    race_of = np.array([row[0] for row in rows])
    data = np.array([row[1:] for row in rows])
    panels = [(race, rim) for race in races for rim in rims]
    fig, axes = plt.subplots(len(panels), 3, figsize=(14, 3.2 * len(panels)), squeeze=False, sharex='col')
    for i, (race, rim) in enumerate(panels):
        for j, inches in enumerate((0.007, 0.014, 0.021)):
            ax = axes[i][j]
            for load in loads:
                sel = ((race_of == race) & (data[:, 0] == inches) & (np.abs(data[:, 1] - rim * 1e6) < 1e-9)
                       & (data[:, 2] == load))
                s = np.concatenate([-data[sel, 3][::-1], data[sel, 3]])
                ax.plot(s, np.concatenate([data[sel, 4][::-1], data[sel, 4]]), label=f'half-space, {load:.0f} N')
            ax.plot(s, np.concatenate([data[sel, 5][::-1], data[sel, 5]]), 'k--', label='package (any load)')
            ax.set_title(f'{race} race, {inches} in pit, rim {rim * 1e6:g} um')
            ax.grid(alpha=0.3)
            ax.set_ylabel('dip (um, + drop)')
            if i == len(panels) - 1:
                ax.set_xlabel("pit centre from the contact's centre (mm)")
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=90)


if __name__ == '__main__':
    main()
