#!/usr/bin/python3
"""Condition indicators of simulated CWRU drive-end faults (docs/health.md, "Simulated and
real CWRU data"): the 6205-2RS at the data set's conditions (config/scenarios/
cwru_drive_end_*hp.yaml: 12 kHz, 49 N, 1797-1730 rpm) with its seeded fault sizes (0.007,
0.014, 0.021 in wide, 0.011 in deep), seen by a housing accelerometer of a given noise
density; prints a Markdown table of RMS, crest factor, kurtosis, the envelope band, the
share of the power below 1 kHz (the rotor's radial mode and the fault's low harmonics: what
lowers the kurtosis of the larger faults), the fault line's envelope SNR, and what the
analyser reports.

    source scripts/env.sh; source build/devel/setup.bash
    dev/cwru_indicators.py                     # 0 hp, 10 ug/sqrt(Hz)
    dev/cwru_indicators.py --hp 3 --noise-ug 1000
"""
import argparse
import pathlib
import sys
import tempfile

import yaml

SOURCE = pathlib.Path(__file__).resolve().parents[1]
CONFIG = SOURCE / 'config'
RPM = {0: 1797.0, 1: 1772.0, 2: 1750.0, 3: 1730.0}  # CWRU Bearing Data Center, 12 kHz drive end
SIZES_IN = (0.007, 0.014, 0.021)
DEPTH_UM = 0.011 * 25400.0  # the EDM faults' depth
SURFACE = {'inner race': 'inner_race', 'ball': 'ball', 'outer race @6:00': 'outer_race'}
LABEL = {'inner race': 'BPFI', 'ball': '2xBSF', 'outer race @6:00': 'BPFO'}
G = 9.80665
OUTPUT_RATE_HZ = 12000.0  # the set's drive-end records
RADIAL_LOAD_N = 49.0  # the 5 kg rotor share's weight, along x (down): config/scenarios/cwru_drive_end_*hp.yaml
NOISE_UG = 10.0  # ug/sqrt(Hz): a good sensor's, so that the simulated columns show the fault's own signal
LOW_HZ = 1000.0  # the power below: the radial mode (~440 Hz) and the fault lines' low harmonics


def housing_sensor(noise_ug=NOISE_UG):
    """The sensor mapping of config/sensors/ct_gantry_housing_accelerometer.yaml adapted to the
    CWRU drive end: a housing accelerometer (the set's sensors sit on the motor housing),
    sampling at the set's 12 kHz, with a range no case reaches, of noise_ug ug/sqrt(Hz)."""
    with open(CONFIG / 'sensors' / 'ct_gantry_housing_accelerometer.yaml', encoding='utf-8') as f:
        sensor = yaml.safe_load(f)['sensor']
    sensor.update(name='CWRU drive end, housing', mount_point_mm=[26.0, 0.0, 0.0], output_rate_Hz=OUTPUT_RATE_HZ,
                  range_g=5000.0, sensitivity_mV_per_g=100.0, noise_density_ug_per_sqrt_Hz=noise_ug, seed=1)
    return sensor


def spall(kind, size_in, position_deg=0.0):
    """The scenario defect of a CWRU seeded fault: kind one of SURFACE's keys (or a surface
    name), EDM width size_in inches, the set's depth; position 0 is 6:00 (the load, along x)."""
    defect = {'type': 'spall', 'at_s': 0.0, 'surface': SURFACE.get(kind, kind), 'position_deg': position_deg,
              'width_mm': size_in * 25.4, 'depth_um': DEPTH_UM}
    if defect['surface'] == 'ball':
        defect['ball'] = 0
    return defect


def scenario(hp, kind, size_in, noise_ug, work):
    import bearing_sim
    sensor_file = pathlib.Path(work) / 'sensor.yaml'
    sensor_file.write_text(bearing_sim.yaml_text({'sensor': housing_sensor(noise_ug)}), encoding='utf-8')
    defects = [] if kind == 'normal' else [spall(kind, size_in)]
    return {'name': 'cwru_indicators', 'duration_s': 1.1, 'seed': 1, 'sample_rate_hz': OUTPUT_RATE_HZ,
            'bearing_file': str(CONFIG / 'bearings' / 'cwru_6205_drive_end.yaml'), 'sensor_file': str(sensor_file),
            'speed': {'initial_speed_rpm': RPM[hp]}, 'load': {'initial': {'force_N': [RADIAL_LOAD_N, 0.0, 0.0]}},
            'defects': defects}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    p.add_argument('--hp', type=int, choices=sorted(RPM), default=0, help='motor load (sets the speed)')
    p.add_argument('--noise-ug', type=float, default=NOISE_UG, help='sensor noise density, ug/sqrt(Hz)')
    args = p.parse_args(argv)
    import math
    import numpy as np
    import bearing_sim
    print('| condition | RMS (g) | crest factor | kurtosis | envelope band (Hz), SK | power < 1 kHz (%) | '
          'fault line SNR (dB) | analyser |')
    print('|---|---|---|---|---|---|---|---|')
    with tempfile.TemporaryDirectory() as work:
        for kind, size in [('normal', 0.0)] + [(k, s) for k in SURFACE for s in SIZES_IN]:
            r = bearing_sim.generate(scenario(args.hp, kind, size, args.noise_ug, work))
            x = r['vibration'][:, 0].astype(float)
            a = bearing_sim.analyze(x, r['info']['measured_rate_hz'], str(CONFIG / 'bearings' / 'cwru_6205_drive_end.yaml'),
                                    window_s=1.0, inner_rad_s=2.0 * math.pi * RPM[args.hp] / 60.0)
            line = next((f for f in a['faults'] if f['label'] == LABEL.get(kind)), None)
            found = [f['fault'] for f in a['faults'] if f['suspected']]
            band = a['envelope_band_hz']
            w = x[-a['samples']:]  # the analysed window
            power = np.abs(np.fft.rfft(w - w.mean())) ** 2
            low = 100.0 * power[np.fft.rfftfreq(w.size, 1.0 / r['info']['measured_rate_hz']) < LOW_HZ].sum() / power.sum()
            snr = f"{line['snr_db']:.0f}" if line else '-'
            print(f"| {kind}{f' {size:.3f} in' if size else ''} | {a['rms_m_s2'] / G:.3g} | {a['crest_factor']:.1f} | "
                  f"{a['kurtosis']:.1f} | {band[0]:.0f}-{band[1]:.0f}, {a['envelope_band_kurtosis']:.1f} | {low:.0f} | "
                  f"{snr} | {', '.join(found) or 'none'} |")
    return 0


if __name__ == '__main__':
    sys.exit(main())
