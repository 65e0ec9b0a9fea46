#!/usr/bin/python3
"""The balls' spin-axis wander read on the real CWRU ball records (docs/cwru_rig.md, "The balls'
spin axis wandering"; docs/model.md 9.5).

Reads a dev/cwru_rig_compare.py comparison.csv simulated without the wander (--bearing: a copy
of config/bearings/cwru_6205_drive_end.yaml with imperfections.ball_spin_axis_wander_deg: 0).
Per ball record, the drop of the 2 x BSF envelope SNR from the simulated record to the real one
is -20 log10 of the share of the time the ball's pit is struck, which with the pit's half width
on the ball gives the standard deviation of its latitude (cwru_measures.spin_axis_wander_deg).
Prints each record's figures and their median. A real record without a line (SNR ~0 dB) gives
a lower bound.

    /usr/bin/python3 dev/cwru_ball_wander.py /tmp/cwru_rig_compare_no_wander/comparison.csv
"""
import argparse
import csv
import math
import pathlib
import sys

import numpy as np
import yaml

import cwru_measures

SOURCE = pathlib.Path(__file__).resolve().parents[1]
BEARING_FILE = SOURCE / 'config' / 'bearings' / 'cwru_6205_drive_end.yaml'


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    p.add_argument('comparison_csv', type=pathlib.Path, help="dev/cwru_rig_compare.py's comparison.csv, no wander")
    p.add_argument('--bearing', type=pathlib.Path, default=BEARING_FILE, help='for the ball diameter')
    args = p.parse_args(argv)
    ball_mm = yaml.safe_load(args.bearing.read_text(encoding='utf-8'))['ball_diameter_mm']
    with open(args.comparison_csv, encoding='utf-8') as f:
        rows = [r for r in csv.DictReader(f) if r['fault'] == 'ball']
    if not rows:
        print(f'cwru_ball_wander: {args.comparison_csv}: no ball records', file=sys.stderr)
        return 2
    sigmas = []
    print('| record | size (in) | hp | 2 x BSF SNR real / simulated (dB) | struck share | wander (deg) |')
    print('|---|---|---|---|---|---|')
    for r in rows:
        real, sim = float(r['real_fault_snr_db']), float(r['sim_fault_snr_db'])
        # The pit's half width as an angle on the ball's great circle.
        half_width_deg = math.degrees(0.5 * float(r['size_in']) * 25.4 / (0.5 * ball_mm))
        sigma = cwru_measures.spin_axis_wander_deg(sim - real, half_width_deg)
        sigmas.append(sigma)
        share = min(1.0, 10.0 ** (-(sim - real) / 20.0))
        print(f"| {r['record']} | {float(r['size_in']):.3f} | {r['load_hp']} | {real:.0f} / {sim:.0f} | "
              f'{share:.2f} | {sigma:.1f} |')
    print(f'\nwander: {min(sigmas):.0f}-{max(sigmas):.0f} deg over {len(sigmas)} records, median '
          f'{np.median(sigmas):.1f} deg')
    return 0


if __name__ == '__main__':
    sys.exit(main())
