"""The condition-monitoring benchmark (bearing_sim.cm_benchmark, docs/health.md "Benchmark")
on a tiny grid, in this process: its scoring rules, and the analyser on cases whose
answer is not in doubt (a large outer-race spall in the load zone of the 6205 under a
good sensor is an outer-race defect and nothing else; a healthy 6205 is healthy). The
envelope band is the analyser's default (the kurtogram's): the 2-4 kHz band at the sensor's
path resonance holds the smooth part of a large 6205 spall's signature and is not
impulsive there, so the evidence rule rightly withholds the outer race in it
(docs/health.md, "Benchmark")."""
import json
import os
import subprocess

import pytest

from conftest import SOURCE


@pytest.fixture(scope='module')
def cmb():
    from bearing_sim import cm_benchmark
    return cm_benchmark


def test_the_installed_entry_point_runs_the_module():
    # scripts/cm_benchmark (installed as `rosrun bearing_sim cm_benchmark`) is the module's main().
    r = subprocess.run(['/usr/bin/python3', str(SOURCE / 'scripts' / 'cm_benchmark'), '--help'],
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=120, env=os.environ)
    assert r.returncode == 0, r.stderr
    assert 'Condition-monitoring benchmark' in r.stdout and '--band' in r.stdout


def tiny_grid(cmb):
    return dict(cmb.FULL, bearings=['6205'], sizes_w_over_d=[0.2], noise_ug_per_sqrt_hz=[10.0], speeds=1, loads=1,
                spall_seeds=1, healthy_seeds=2, window_s=0.5, band='kurtogram')


def test_scoring_rules(cmb):
    assert cmb.classify(set()) == 'none'
    assert cmb.classify({'outer'}) == 'outer'
    assert cmb.classify({'ball', 'cage'}) == 'ball'       # a ball spall's cage modulation is allowed
    assert cmb.classify({'outer', 'cage'}) == 'multiple'  # beside a race defect it is another type
    assert cmb.classify({'outer', 'inner'}) == 'multiple'
    assert cmb.classify({'cage'}) == 'cage'


def test_grid_positions_follow_the_load_zone(cmb):
    cases = cmb.build_cases(tiny_grid(cmb))
    # 6205: the outer race stands, so its spalls are in and out of the load zone; the
    # inner race and the ball turn through it.
    assert {(c['truth'], c['position']) for c in cases} == {
        ('none', '-'), ('outer', 'in_zone'), ('outer', 'out_of_zone'), ('inner', 'rotating'), ('ball', 'rotating')}
    assert len({c['seed'] for c in cases}) == len(cases) == 6


def test_tiny_benchmark(cmb, tmp_path):
    cases = cmb.build_cases(tiny_grid(cmb))
    assert len(cases) <= 6
    rows = cmb.run_cases(cases, str(tmp_path / 'inputs'), workers=0, log=None)
    assert [r['error'] for r in rows] == [''] * len(rows)
    by = {(r['truth'], r['position']): r for r in rows}
    # A 1.6 mm x 20 um outer-race spall in the load zone, 900 rpm, 500 N, 10 ug/sqrt(Hz):
    # the outer race and nothing beside it, with a clear fundamental and 2nd harmonic.
    outer = by[('outer', 'in_zone')]
    assert outer['finding'] == 'outer' and outer['predicted'] == 'outer'
    assert outer['outer_snr_db'] >= 12.0 and outer['outer_h2_snr_db'] >= 10.0
    # Found in an impulsive band (the rule asks it of the stationary race: SK >= 2).
    assert outer['band_sk'] >= 2.0 and outer['clipped_samples'] == 0
    # The inner-race spall turns through the load zone: inner race, with its sidebands.
    inner = by[('inner', 'rotating')]
    assert inner['predicted'] == 'inner' and inner['inner_sb_required'] == 1 and inner['inner_sb_snr_db'] >= 10.0
    healthy = [r for r in rows if r['truth'] == 'none']
    assert len(healthy) == 2 and all(r['predicted'] == 'none' for r in healthy)

    summary = cmb.summarize(rows)
    counts = summary['confusion_matrix']['counts']
    assert sum(sum(row.values()) for row in counts.values()) == len(rows) == summary['cases']
    for truth in cmb.TRUTHS:
        assert sum(counts[truth].values()) == sum(r['truth'] == truth for r in rows)
    assert summary['false_alarm']['of'] == 2 and summary['false_alarm']['count'] == 0
    lo, hi = summary['false_alarm']['ci95']
    assert lo == 0.0 and 0.5 < hi < 1.0  # Clopper-Pearson for 0 of 2: 1 - 0.025^(1/2) = 0.842
    assert hi == pytest.approx(1.0 - 0.025 ** 0.5, rel=1e-9)
    json.dumps(summary)  # plain values only

    cmb.write_csv(rows, tmp_path / 'results.csv')
    assert len((tmp_path / 'results.csv').read_text().splitlines()) == len(rows) + 1
