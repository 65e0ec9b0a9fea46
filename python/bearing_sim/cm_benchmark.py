"""Condition-monitoring benchmark: can the envelope analyser's diagnosis be trusted?

Generates a grid of simulated runs (bearing x defect type x spall size x position
relative to the load zone x speed x load x sensor noise x seed), each a scenario of
`bearing_sim.generate` with a virtual accelerometer, runs `bearing_sim.analyze` on the
measured signal with the right ring speeds (the analyser's defaults: kurtogram band,
evidence rule of docs/health.md; or --band resonance: the band at the sensor's path
resonance) and scores what the analyser suspects against the truth.

    rosrun bearing_sim cm_benchmark --out /tmp/cm_benchmark                 # full grid (docs/health.md, "Benchmark")
    rosrun bearing_sim cm_benchmark --out /tmp/cm_benchmark_res --band resonance
    rosrun bearing_sim cm_benchmark --quick --out /tmp/cm_quick --workers 2  # a few dozen cases
    (or python3 -m bearing_sim.cm_benchmark ...; the bearing and sensor files come from the
    package's config/, in the source tree or the install space)

Writes into --out:
  results.csv     one row per case: its parameters, the truth, the finding, the evidence
                  (fundamental, 2nd harmonic and best sideband SNR of BPFO, BPFI, 2xBSF, FTF)
  summary.json    confusion matrix, false-alarm rate on healthy runs with its 95 %
                  Clopper-Pearson interval, detection and right-type rate per size bin (all
                  bearings and per bearing), the "other type beside the right one" rate, the
                  size threshold above which the right type is found in >= 95 % of spalls
  benchmark.png   confusion matrix and right-type rate against spall size, per bearing

Scoring rules (also in docs/health.md, "Benchmark"):
  * The finding of a case is the set of fault types the analyser suspects
    (`faults[i]['suspected']`): BPFO -> outer, BPFI -> inner, 2xBSF -> ball, FTF -> cage.
  * Predicted class (a column of the confusion matrix):
      none     nothing suspected;
      outer / inner / ball
               exactly one of outer, inner, ball is suspected and cage is not, except that
               "ball" may come with "cage" (a ball spall is carried round at the cage
               speed, so its envelope is modulated at FTF);
      cage     only the cage line is suspected;
      multiple anything else (two race/ball types, or a race type with the cage line).
  * False alarm: a healthy case (no spall) whose predicted class is not "none"
    (a lone cage finding counts as a false alarm).
  * Right type: a spall case whose predicted class is its defect type. A ball spall with
    ball + cage counts as right; an outer-race spall with outer + cage does not.
  * Detected: a spall case whose finding contains its defect type (other types may be
    beside it).
  * Other type beside the right one: a detected spall case whose predicted class is
    "multiple" (its type and another one); the rate is over the detected spall cases.
  * Size: the spall width relative to the ball diameter, w/D (the depth a ball can reach
    in a spall is min(h, w^2/(4 D)), so w/D scales the impact the same way on every
    bearing). The stated size threshold is the smallest grid size from which on every
    larger size bin reaches a right-type rate of >= 95 % over all bearings; it is read from
    the results, not fixed beforehand.

The load acts on the rotating ring along +x. The load zone's centre is the azimuth of the
most heavily loaded ball at the static equilibrium (0 deg when the inner ring turns, 180
deg when the outer ring turns: the ring is pushed towards +x): a spall on the stationary
race there is "in_zone", 180 deg away "out_of_zone". A spall on the rotating race or on a ball passes through the load zone once
per turn (of the ring, of the cage), so its position is a phase only ("rotating").

Parallel: a Dask LocalCluster of --workers single-threaded processes (as
bearing_sim.campaign), or --workers 0 to run in this process (tests).
"""
import argparse
import csv
import hashlib
import itertools
import json
import logging
import math
import os
import pathlib
import sys
import time

import yaml

from bearing_sim.config_files import config_file

TYPES = ('outer', 'inner', 'ball')
SURFACE = {'outer': 'outer_race', 'inner': 'inner_race', 'ball': 'ball'}
FAULT_TYPE = {'BPFO': 'outer', 'BPFI': 'inner', '2xBSF': 'ball', 'FTF': 'cage'}
TRUTHS = ('none',) + TYPES
PREDICTED = ('none', 'outer', 'inner', 'ball', 'cage', 'multiple')
RIGHT_TYPE_TARGET = 0.95
# The housing sensor sees the bare ring's acceleration through the path resonance (x10 at
# 3 kHz; docs/sensor.md: no housing mass in the model), so a 6205 with a large spall
# reaches 500 g at the sensor and the shipped +-50 g range clips it, which removes the
# impacts from the envelope. A range no case reaches keeps the benchmark about the
# analyser (results.csv counts clipped samples: 0 expected).
SENSOR_RANGE_G = 5000.0
FALSE_ALARM_TARGET = 0.01

# The bearings of the benchmark: a small deep-groove bearing (inner ring turning, outer
# race stationary), an angular contact pair and the CT gantry bearing (both with the outer
# ring turning, inner race stationary). Each with imperfections (ball size scatter, ball
# spacing scatter, cage slip, so a healthy run is not an ideal bearing), a housing
# accelerometer on the stationary ring (the shipped CT sensor, moved, with a +-5000 g range,
# see SENSOR_RANGE_G), two speeds and two loads. No race roughness: the model's roughness
# is a frozen profile that repeats at the ball-pass frequencies (docs/bearing_file.md),
# i.e. deterministic BPFO/BPFI lines a real bearing does not have (with 0.02 um on the CT
# bearing at 180 rpm, 6 of 24 healthy runs were reported as race defects; 0 of 24 without).
BEARINGS = {
    '6205': {
        'file': 'deep_groove_6205.yaml',
        'title': '6205 deep groove (inner ring turns)',
        'rate_hz': 20000.0,
        'sensor': {'mount_point_mm': [26.0, 0.0, 0.0], 'output_rate_Hz': 20000.0},
        'speeds_rpm': [900.0, 1800.0],
        'loads': [{'force_N': [500.0, 0.0, 0.0]}, {'force_N': [2000.0, 0.0, 200.0]}],
        'imperfections': {'roughness_rms_um': 0.0, 'ball_diameter_variation_um': 0.1,
                          'ball_spacing_jitter_mm': 0.05, 'cage_slip_percent': 0.5,
                          'cage_slip_variation_percent': 0.2},
    },
    'ins_618_22_db': {
        'file': 'ins_618_22_db.yaml',
        'title': '618/22 DB angular contact pair (outer ring turns)',
        'rate_hz': 20000.0,
        'sensor': {'mount_point_mm': [11.0, 0.0, 0.0], 'output_rate_Hz': 20000.0},
        'speeds_rpm': [600.0, 1500.0],
        'loads': [{'force_N': [50.0, 0.0, 20.0]}, {'force_N': [200.0, 0.0, 20.0]}],
        'imperfections': {'roughness_rms_um': 0.0, 'ball_diameter_variation_um': 0.05,
                          'ball_spacing_jitter_mm': 0.03, 'cage_slip_percent': 0.5,
                          'cage_slip_variation_percent': 0.2},
    },
    'ct_gantry_lyc': {
        'file': 'ct_gantry_lyc.yaml',
        'title': 'CT gantry LYC, 2 x 207 balls (outer ring turns)',
        'rate_hz': 10000.0,
        'sensor': {'mount_point_mm': [501.0, 0.0, 0.0], 'output_rate_Hz': 10000.0},
        'speeds_rpm': [60.0, 180.0],
        'loads': [{'force_N': [6800.0, 0.0, 0.0], 'moment_Nm': [0.0, 2100.0]},
                  {'force_N': [3000.0, 0.0, 0.0], 'moment_Nm': [0.0, 0.0]}],
        'imperfections': {'roughness_rms_um': 0.0, 'ball_diameter_variation_um': 0.2,
                          'ball_spacing_jitter_mm': 0.1, 'cage_slip_percent': 0.5,
                          'cage_slip_variation_percent': 0.2},
    },
}

# The grid. Sizes are spall widths relative to the ball diameter (0.01 D is incipient:
# 0.08 mm on the 6205, a 0.2 um deep dip; 0.2 D a large spall).
FULL = {
    'bearings': list(BEARINGS),
    'sizes_w_over_d': [0.005, 0.01, 0.02, 0.05, 0.1, 0.2],
    'depth_um': 20.0,
    # White noise density at the sensor: 10 ug/sqrt(Hz) a good IEPE accelerometer,
    # 1 mg/sqrt(Hz) a noisy MEMS sensor, 10 mg/sqrt(Hz) stands for a machine's broadband
    # background (other machinery, flow, electrical pick-up).
    'noise_ug_per_sqrt_hz': [10.0, 1000.0, 10000.0],
    'speeds': 2,           # the first n speeds and loads of each bearing
    'loads': 2,
    'spall_seeds': 3,      # seeds per spall case
    'healthy_seeds': 30,   # seeds per healthy (bearing, speed, load, noise)
    'settle_s': 0.1,       # dropped before the analysis window
    'window_s': 1.0,
}
# A few dozen cases: one speed and load per bearing, two sizes, 0.5 s windows.
QUICK = dict(FULL, sizes_w_over_d=[0.02, 0.1], noise_ug_per_sqrt_hz=[1000.0], speeds=1, loads=1, spall_seeds=1,
             healthy_seeds=2, window_s=0.5)


_zones = {}


def load_zone_deg(name, load_index):
    """Azimuth (deg, bearing frame) of the most heavily loaded ball at the static
    equilibrium under the case's load: the centre of the load zone on the stationary race.
    The load acts on the rotating ring, so the zone is at 0 deg when the inner ring turns
    (it is pushed towards +x) and at 180 deg when the outer ring turns."""
    key = (name, load_index)
    if key not in _zones:
        import bearing_sim
        import numpy as np
        load = BEARINGS[name]['loads'][load_index]
        eq = bearing_sim.static_equilibrium(str(config_file('bearings/' + BEARINGS[name]['file'])),
                                            force_N=load['force_N'], moment_Nm=load.get('moment_Nm', (0.0, 0.0)))
        az = float(np.degrees(eq['ball_azimuth_rad'][int(np.argmax(eq['ball_load_N']))]))
        _zones[key] = round(az % 360.0, 1)
    return _zones[key]


def case_seed(case_id):
    return int(hashlib.sha256(case_id.encode()).hexdigest()[:8], 16) % 1000000


def build_cases(grid):
    """The cases of a grid: list of dicts of plain values (the rows' parameters)."""
    cases = []
    for name in grid['bearings']:
        b = BEARINGS[name]
        stationary = 'outer' if _rotating_ring(b) == 'inner' else 'inner'
        for speed, li, noise in itertools.product(b['speeds_rpm'][:grid['speeds']], range(len(b['loads'][:grid['loads']])),
                                                  grid['noise_ug_per_sqrt_hz']):
            common = {'bearing': name, 'speed_rpm': speed, 'load': li, 'noise_ug_per_sqrt_hz': noise}
            for s in range(grid['healthy_seeds']):
                cases.append(dict(common, truth='none', size_w_over_d=0.0, width_mm=0.0, position='-',
                                  position_deg=0.0, seed_index=s))
            for kind, size in itertools.product(TYPES, grid['sizes_w_over_d']):
                zone = load_zone_deg(name, li)
                positions = ([('in_zone', zone), ('out_of_zone', (zone + 180.0) % 360.0)] if kind == stationary
                             else [('rotating', 0.0)])
                for (pos, deg), s in itertools.product(positions, range(grid['spall_seeds'])):
                    cases.append(dict(common, truth=kind, size_w_over_d=size, position=pos, position_deg=deg,
                                      seed_index=s))
    for c in cases:
        c['id'] = '_'.join(str(c[k]) for k in ('bearing', 'truth', 'size_w_over_d', 'position', 'speed_rpm',
                                                 'load', 'noise_ug_per_sqrt_hz', 'seed_index'))
        c['seed'] = case_seed(c['id'])
        c['settle_s'], c['window_s'], c['depth_um'] = grid['settle_s'], grid['window_s'], grid['depth_um']
        c['band'] = grid.get('band', 'kurtogram')
    return cases


_bearing_docs = {}


def _bearing_doc(name):
    if name not in _bearing_docs:
        with open(config_file('bearings/' + BEARINGS[name]['file']), encoding='utf-8') as f:
            _bearing_docs[name] = yaml.safe_load(f)
    return _bearing_docs[name]


def _rotating_ring(b):
    with open(config_file('bearings/' + b['file']), encoding='utf-8') as f:
        return yaml.safe_load(f).get('rotating_ring', 'inner')


def _write_once(directory, doc):
    """Writes a YAML document under a name from its content; returns the path."""
    import bearing_sim
    text = bearing_sim.yaml_text(doc)
    os.makedirs(directory, exist_ok=True)
    path = pathlib.Path(directory) / (hashlib.sha256(text.encode()).hexdigest()[:16] + '.yaml')
    if not path.exists():
        tmp = path.with_suffix(f'.{os.getpid()}.tmp')
        tmp.write_text(text, encoding='utf-8')
        os.replace(tmp, path)
    return str(path)


def scenario_of(case, work_dir):
    """The scenario dict of a case (bearing and sensor files written into work_dir)."""
    b = BEARINGS[case['bearing']]
    bearing = dict(_bearing_doc(case['bearing']))
    bearing['imperfections'] = dict(b['imperfections'], seed=case['seed'])
    bearing.pop('defects', None)
    with open(config_file('sensors/ct_gantry_housing_accelerometer.yaml'), encoding='utf-8') as f:
        sensor = yaml.safe_load(f)['sensor']
    sensor.update(b['sensor'], name=f"{case['bearing']} housing, radial", range_g=SENSOR_RANGE_G,
                  sensitivity_mV_per_g=10.0,
                  noise_density_ug_per_sqrt_Hz=case['noise_ug_per_sqrt_hz'], seed=case['seed'])
    ball_d_mm = bearing['ball_diameter_mm']
    defects = []
    if case['truth'] != 'none':
        spall = {'type': 'spall', 'at_s': 0.0, 'surface': SURFACE[case['truth']],
                 'position_deg': case['position_deg'], 'width_mm': case['size_w_over_d'] * ball_d_mm,
                 'depth_um': case['depth_um']}
        if case['truth'] == 'ball':
            spall['ball'] = 0
        defects.append(spall)
    return {
        'name': 'cm_benchmark',
        'duration_s': case['settle_s'] + case['window_s'],
        'seed': case['seed'],
        'sample_rate_hz': b['rate_hz'],
        'bearing_file': _write_once(work_dir, bearing),
        'sensor_file': _write_once(work_dir, {'sensor': sensor}),
        'speed': {'initial_speed_rpm': case['speed_rpm']},
        'load': {'initial': dict(b['loads'][case['load']])},
        'defects': defects,
    }


def classify(suspected):
    """Predicted class of a set of suspected fault types (module docstring, scoring rules)."""
    races = suspected & set(TYPES)
    if not suspected:
        return 'none'
    if not races:
        return 'cage'
    if len(races) == 1:
        (kind,) = races
        if 'cage' not in suspected or kind == 'ball':
            return kind
    return 'multiple'


def run_case(case, work_dir):
    """Generates and analyses one case; returns its results row (never raises: a failing
    case is a row with its error)."""
    import bearing_sim
    row = {k: case[k] for k in ('id', 'band', 'bearing', 'truth', 'size_w_over_d', 'position', 'position_deg', 'speed_rpm',
                                'load', 'noise_ug_per_sqrt_hz', 'seed_index', 'seed')}
    b = BEARINGS[case['bearing']]
    t0 = time.perf_counter()
    try:
        sc = scenario_of(case, work_dir)
        row['width_mm'] = sc['defects'][0]['width_mm'] if sc['defects'] else 0.0
        row['load_N'] = json.dumps(b['loads'][case['load']])
        r = bearing_sim.generate(sc)
        x = r['vibration'][:, 0].astype(float)
        rate = r['info']['measured_rate_hz']
        w = 2.0 * math.pi * case['speed_rpm'] / 60.0
        rings = {'inner_rad_s': w} if _rotating_ring(b) == 'inner' else {'outer_rad_s': w}
        if case.get('band', 'kurtogram') == 'resonance':  # the sensor's path resonance +- 1 kHz
            rings.update(resonance_hz=b['sensor'].get('path_resonance_Hz', 3000.0), band_width_hz=2000.0)
        a = bearing_sim.analyze(x, rate, sc['bearing_file'], window_s=case['window_s'], **rings)
        suspected = set()
        for f in a['faults']:
            kind = FAULT_TYPE[f['label']]
            if f['suspected']:
                suspected.add(kind)
            h = f['harmonics']
            row[f'{kind}_snr_db'] = round(f['snr_db'], 2)
            row[f'{kind}_h2_snr_db'] = round(h[1][1], 2) if len(h) > 1 else ''
            row[f'{kind}_sb_snr_db'] = round(max(sb[1] for sb in f['sidebands']), 2) if f['sidebands'] else ''
            row[f'{kind}_sb_required'] = int(f['sidebands_required'])
            # Evidence in detail (frequencies as found), for studying the rules offline.
            row[f'{kind}_hz'] = round(f['frequency_hz'], 3)
            row[f'{kind}_expected_hz'] = round(f['expected_hz'], 3)
            row[f'{kind}_h3_snr_db'] = round(h[2][1], 2) if len(h) > 2 else ''
            row[f'{kind}_harmonics_found'] = f['harmonics_found']
            for side, sb in zip(('lo', 'hi'), f['sidebands']):
                row[f'{kind}_sb_{side}_hz'], row[f'{kind}_sb_{side}_snr_db'] = round(sb[0], 3), round(sb[1], 2)
            row[f'{kind}_suspected'] = int(f['suspected'])
            row[f'{kind}_note'] = f.get('note', '')
        row['band_sk'] = round(a['envelope_band_kurtosis'], 4)
        row['band_sk_samples'] = round(a['envelope_band_independent_samples'], 1)
        row['clipped_samples'] = int((abs(x) >= 0.999 * SENSOR_RANGE_G * 9.80665).sum())
        row.update(finding='+'.join(sorted(suspected)) or 'none', predicted=classify(suspected),
                   health=a['health'], kurtosis=round(a['kurtosis'], 3), rms_m_s2=round(a['rms_m_s2'], 4),
                   band_hz='-'.join(f'{v:.0f}' for v in a['envelope_band_hz']), error='')
    except Exception as e:  # recorded, the benchmark goes on
        row.update(finding='', predicted='error', error=f'{type(e).__name__}: {e}')
    row['wall_s'] = round(time.perf_counter() - t0, 3)
    return row


def run_cases(cases, work_dir, workers=0, log=print):
    os.makedirs(work_dir, exist_ok=True)
    rows = []
    if workers == 0:
        for i, c in enumerate(cases):
            rows.append(run_case(c, work_dir))
            if log and (i + 1) % 50 == 0:
                log(f'{i + 1}/{len(cases)} cases')
        return rows
    from dask.distributed import Client, LocalCluster, as_completed
    # One single-threaded process per worker, as bearing_sim.campaign.
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                      silence_logs=logging.ERROR) as cluster, Client(cluster) as client:
        futures = client.map(run_case, cases, [work_dir] * len(cases), pure=False)
        for i, fut in enumerate(as_completed(futures)):
            rows.append(fut.result())
            fut.release()
            if log and (i + 1) % 50 == 0:
                log(f'{i + 1}/{len(cases)} cases')
    order = {c['id']: i for i, c in enumerate(cases)}
    return sorted(rows, key=lambda r: order[r['id']])


def clopper_pearson(k, n, level=0.95):
    from scipy.stats import beta
    if n == 0:
        return (0.0, 1.0)
    a = (1.0 - level) / 2.0
    lo = 0.0 if k == 0 else float(beta.ppf(a, k, n - k + 1))
    hi = 1.0 if k == n else float(beta.ppf(1.0 - a, k + 1, n - k))
    return (lo, hi)


def _rate(k, n):
    lo, hi = clopper_pearson(k, n)
    return {'count': k, 'of': n, 'rate': (k / n) if n else None, 'ci95': [lo, hi]}


def summarize(rows):
    ok = [r for r in rows if r['predicted'] != 'error']
    confusion = {t: {p: 0 for p in PREDICTED} for t in TRUTHS}
    for r in ok:
        confusion[r['truth']][r['predicted']] += 1
    healthy = [r for r in ok if r['truth'] == 'none']
    spalls = [r for r in ok if r['truth'] != 'none']

    def detected(r):
        return r['truth'] in r['finding'].split('+')

    def scores(rs):
        det = [r for r in rs if detected(r)]
        return {'cases': len(rs),
                'detected': _rate(len(det), len(rs)),
                'right_type': _rate(sum(r['predicted'] == r['truth'] for r in rs), len(rs)),
                'other_type_beside_right': _rate(sum(r['predicted'] == 'multiple' for r in det), len(det))}

    sizes = sorted({r['size_w_over_d'] for r in spalls})
    by_size = {str(s): scores([r for r in spalls if r['size_w_over_d'] == s]) for s in sizes}

    def size_threshold(table):
        # Only the sizes that have cases in this table (a --limit subset or one bearing may miss some).
        measured = [t for t in sizes if table.get(str(t), {}).get('right_type', {}).get('rate') is not None]
        for s in measured:
            if all(table[str(t)]['right_type']['rate'] >= RIGHT_TYPE_TARGET for t in measured if t >= s):
                return s
        return None
    threshold = size_threshold(by_size)
    above = [r for r in spalls if threshold is not None and r['size_w_over_d'] >= threshold]
    groups = {}
    for key in ('bearing', 'truth', 'position', 'noise_ug_per_sqrt_hz', 'speed_rpm'):
        groups[key] = {str(v): scores([r for r in spalls if r[key] == v]) for v in sorted({r[key] for r in spalls}, key=str)}
    per_bearing_size = {b: {str(s): scores([r for r in spalls if r['bearing'] == b and r['size_w_over_d'] == s])
                            for s in sizes} for b in sorted({r['bearing'] for r in spalls})}
    fa_by = {}
    for key in ('bearing', 'noise_ug_per_sqrt_hz'):
        fa_by[key] = {str(v): _rate(sum(r['predicted'] != 'none' for r in healthy if r[key] == v),
                                    sum(1 for r in healthy if r[key] == v)) for v in sorted({r[key] for r in healthy}, key=str)}
    fa = _rate(sum(r['predicted'] != 'none' for r in healthy), len(healthy))
    summary = {
        'cases': len(rows), 'errors': len(rows) - len(ok),
        'confusion_matrix': {'rows_truth': list(TRUTHS), 'columns_predicted': list(PREDICTED), 'counts': confusion},
        'false_alarm': fa,
        'false_alarm_by': fa_by,
        'false_alarm_findings': sorted({r['finding'] for r in healthy if r['predicted'] != 'none'}),
        'healthy_health_not_ok': _rate(sum(r['health'] != 'OK' for r in healthy), len(healthy)),
        'spalls_all_sizes': scores(spalls),
        'by_size_w_over_d': by_size,
        'by_bearing_and_size': per_bearing_size,
        'by': groups,
        'size_threshold_w_over_d': threshold,
        'size_threshold_by_bearing': {b: size_threshold(t) for b, t in per_bearing_size.items()},
        # per bearing, defect type and position: right-type rate per size and the group's threshold
        'by_group_and_size': {
            g: {'right_type_by_size': {str(sz): t[str(sz)]['right_type']['rate'] for sz in sizes},
                'size_threshold_w_over_d': size_threshold(t)}
            for g, t in {f'{b}/{k}/{p}': {str(sz): scores([r for r in spalls if (r['bearing'], r['truth'], r['position'],
                                                                                 r['size_w_over_d']) == (b, k, p, sz)])
                                            for sz in sizes}
                         for b, k, p in sorted({(r['bearing'], r['truth'], r['position']) for r in spalls})}.items()},
        'by_bearing_and_noise_large': {  # spalls of w/D >= 0.05
            b: {str(n): scores([r for r in spalls if r['bearing'] == b and r['noise_ug_per_sqrt_hz'] == n
                                and r['size_w_over_d'] >= 0.05])
                for n in sorted({r['noise_ug_per_sqrt_hz'] for r in spalls})} for b in per_bearing_size},
        'above_threshold': scores(above) if above else None,
        'targets': {'false_alarm_max': FALSE_ALARM_TARGET, 'right_type_min': RIGHT_TYPE_TARGET},
    }
    summary['pass'] = {
        'false_alarm': fa['rate'] is not None and fa['rate'] <= FALSE_ALARM_TARGET,
        'right_type_above_threshold': threshold is not None,
        'no_other_type_above_threshold': bool(above) and summary['above_threshold']['other_type_beside_right']['count'] == 0,
    }
    return summary


def plot(rows, summary, path):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    import numpy as np
    names = [b for b in BEARINGS if any(r['bearing'] == b for r in rows)]
    fig, axes = plt.subplots(2, len(names), figsize=(5.2 * len(names), 9.0), squeeze=False)
    for j, name in enumerate(names):
        ax = axes[0][j]
        m = np.zeros((len(TRUTHS), len(PREDICTED)), dtype=int)
        for r in rows:
            if r['bearing'] == name and r['predicted'] != 'error':
                m[TRUTHS.index(r['truth']), PREDICTED.index(r['predicted'])] += 1
        frac = m / np.maximum(m.sum(axis=1, keepdims=True), 1)
        ax.imshow(frac, cmap='Blues', vmin=0, vmax=1)
        for i in range(m.shape[0]):
            for k in range(m.shape[1]):
                ax.text(k, i, str(m[i, k]), ha='center', va='center', color='white' if frac[i, k] > 0.6 else 'black')
        ax.set_xticks(range(len(PREDICTED)), PREDICTED, rotation=30)
        ax.set_yticks(range(len(TRUTHS)), TRUTHS)
        ax.set_xlabel('predicted')
        ax.set_ylabel('truth')
        ax.set_title(BEARINGS[name]['title'], fontsize=9)
        ax = axes[1][j]
        for kind, style in zip(TYPES, ('o-', 's-', '^-')):
            sizes = sorted({r['size_w_over_d'] for r in rows if r['bearing'] == name and r['truth'] == kind})
            rate = []
            for s in sizes:
                rs = [r for r in rows if r['bearing'] == name and r['truth'] == kind and r['size_w_over_d'] == s
                      and r['predicted'] != 'error']
                rate.append(100.0 * sum(r['predicted'] == kind for r in rs) / max(len(rs), 1))
            ax.plot(sizes, rate, style, label=f'{kind}: right type')
        sizes = sorted({r['size_w_over_d'] for r in rows if r['bearing'] == name and r['truth'] != 'none'})
        det = []
        for s in sizes:
            rs = [r for r in rows if r['bearing'] == name and r['truth'] != 'none' and r['size_w_over_d'] == s
                  and r['predicted'] != 'error']
            det.append(100.0 * sum(r['truth'] in r['finding'].split('+') for r in rs) / max(len(rs), 1))
        ax.plot(sizes, det, 'k--', lw=1, label='all types: detected')
        ax.axhline(100 * RIGHT_TYPE_TARGET, color='r', lw=0.8, ls=':')
        if summary['size_threshold_w_over_d'] is not None:
            ax.axvline(summary['size_threshold_w_over_d'], color='g', lw=0.8, ls=':')
        if sizes:  # a --limit subset may hold no spall case of this bearing: nothing to put on a log axis
            ax.set_xscale('log')
        ax.set_ylim(-3, 103)
        d = _bearing_doc(name)['ball_diameter_mm']
        ax.set_xlabel(f'spall width / ball diameter (D = {d:g} mm)')
        ax.set_ylabel('% of spall cases')
        ax.grid(True, which='both', alpha=0.3)
        ax.legend(fontsize=8, loc='lower right')
    fa = summary['false_alarm']
    th = summary['size_threshold_w_over_d']
    band = {'kurtogram': "analyser's default band (kurtogram)", 'resonance': 'band at the sensor resonance (2-4 kHz)'}
    fig.suptitle(f"Envelope diagnosis, {band[rows[0].get('band', 'kurtogram')]}: {summary['cases']} cases; "
                 f"false alarms {fa['count']}/{fa['of']} healthy runs; "
                 + (f'right type >= 95 % from w/D = {th}' if th is not None else 'no spall size reaches 95 % right type'),
                 fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def write_csv(rows, path):
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(path, 'w', newline='', encoding='utf-8') as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split('\n\n')[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--out', required=True, help='output directory')
    p.add_argument('--quick', action='store_true', help='a small grid (a few dozen cases, 0.5 s windows)')
    p.add_argument('--workers', type=int, default=len(os.sched_getaffinity(0)),
                   help='Dask LocalCluster worker processes (default: the usable cores); 0: in this process')
    p.add_argument('--bearings', default=None, help='comma-separated subset of ' + ','.join(BEARINGS))
    p.add_argument('--window-s', type=float, default=None, help='analysis window (s), instead of the grid\'s')
    p.add_argument('--band', choices=('kurtogram', 'resonance'), default='kurtogram',
                   help="envelope band: the analyser's default (kurtogram) or the sensor's path resonance "
                        '(3 kHz +- 1 kHz, resonance_hz of analyze)')
    p.add_argument('--limit', type=int, default=0, help='only every k-th case so that about this many remain')
    args = p.parse_args(argv)
    grid = dict(QUICK if args.quick else FULL)
    grid['band'] = args.band
    if args.window_s:
        grid['window_s'] = args.window_s
    if args.bearings:
        grid['bearings'] = args.bearings.split(',')
    cases = build_cases(grid)
    if args.limit and args.limit < len(cases):
        step = len(cases) / args.limit
        cases = [cases[int(i * step)] for i in range(args.limit)]
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    import bearing_sim
    cpu = bearing_sim.cpu_model_name()
    print(f'{len(cases)} cases on {max(args.workers, 1)} worker(s), {cpu}', flush=True)
    t0 = time.perf_counter()
    rows = run_cases(cases, str(out / 'inputs'), args.workers, log=lambda s: print(s, flush=True))
    wall = time.perf_counter() - t0
    write_csv(rows, out / 'results.csv')
    summary = summarize(rows)
    summary.update(grid=grid, wall_s=round(wall, 1), workers=args.workers, cpu=cpu,
                   case_wall_s_sum=round(sum(r['wall_s'] for r in rows), 1))
    (out / 'summary.json').write_text(json.dumps(summary, indent=1), encoding='utf-8')
    plot(rows, summary, out / 'benchmark.png')
    fa, ab = summary['false_alarm'], summary['above_threshold']
    print(f"false alarms {fa['count']}/{fa['of']} (95 % CI {100 * fa['ci95'][0]:.2f}-{100 * fa['ci95'][1]:.2f} %); "
          f"size threshold w/D {summary['size_threshold_w_over_d']}"
          + (f"; above it right type {ab['right_type']['count']}/{ab['right_type']['of']}, other type beside "
             f"the right one {ab['other_type_beside_right']['count']}/{ab['other_type_beside_right']['of']}" if ab else '')
          + f"; {summary['errors']} errors; {wall:.0f} s wall")
    return 0 if summary['errors'] == 0 else 1


if __name__ == '__main__':
    # Through the module's own name, so that Dask's workers import run_case rather than
    # receive a copy of this __main__ (python3 -m bearing_sim.cm_benchmark).
    from bearing_sim import cm_benchmark
    sys.exit(cm_benchmark.main())
