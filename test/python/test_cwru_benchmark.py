"""bearing_sim.cwru_benchmark without the real CWRU data: its tables and file naming, its
scoring rules on hand-made verdicts, and the whole command on small synthetic .mat files
whose answer is not in doubt (an outer-race impact train at BPFO; Gaussian noise)."""
import csv
import json
import math
import subprocess
import sys

import numpy as np
import pytest
import scipy.io

from bearing_sim import cwru_benchmark, cwru_records, cwru_scoring

G = 9.80665
BPFO_PER_REV = 3.5848  # CWRU's drive-end 6205: BPFO / f_r
FAN_END_BPFO_PER_REV = 3.0530  # the fan-end 6203 (CWRU's bearing page)


def outer_race_train(rpm, fs=12000.0, duration_s=3.0, seed=1, bpfo_per_rev=BPFO_PER_REV):
    """Impacts at BPFO, each ringing a 3 kHz resonance (5 % damped), over a little noise; in g."""
    n = int(fs * duration_s)
    impacts = np.zeros(n)
    bpfo = bpfo_per_rev * rpm / 60.0
    impacts[(np.arange(0.0, duration_s, 1.0 / bpfo) * fs).astype(int)] = 1.0
    t = np.arange(int(0.02 * fs)) / fs
    wn = 2.0 * math.pi * 3000.0
    ring = np.exp(-0.05 * wn * t) * np.sin(wn * t)
    noise = 0.05 * np.random.default_rng(seed).standard_normal(n)
    return np.convolve(impacts, ring)[:n] + noise


@pytest.fixture(scope='module')
def run(tmp_path_factory):
    """The command on record 130 (outer race, own speed), record 97 (normal, 48 kHz, no RPM
    variable), a file that is not MATLAB, a fan-end record (294: outer race of the 6203, its
    own channel) and a file of no record of the table."""
    data = tmp_path_factory.mktemp('cwru')
    scipy.io.savemat(data / '130.mat', {'X130_DE_time': outer_race_train(1797.0)[:, None],
                                        'X130_FE_time': np.zeros((10, 1)), 'X130RPM': np.array([[1797]])})
    noise = 0.05 * np.random.default_rng(2).standard_normal(int(48000 * 2.0))
    scipy.io.savemat(data / 'normal_0_97.mat', {'X097_DE_time': noise[:, None]})
    (data / '12k_Drive_End_OR007@6_1_131.mat').write_bytes(b'not a MATLAB file')
    # The fan-end channel holds the 6203's BPFO train, the drive-end one noise: read the wrong
    # channel or the wrong bearing and the outer race is not found.
    scipy.io.savemat(data / '12k_Fan_End_OR007@6_0_294.mat',
                     {'X294_FE_time': outer_race_train(1797.0, bpfo_per_rev=FAN_END_BPFO_PER_REV)[:, None],
                      'X294_DE_time': noise[:12000 * 3, None], 'X294RPM': np.array([[1797]])})
    (data / '12k_Drive_End_XX_999.mat').write_bytes(b'')
    out = tmp_path_factory.mktemp('out')
    assert cwru_benchmark.main([str(data), '--out', str(out)]) == 0
    with open(out / 'records.csv', newline='') as f:
        rows = {int(r['record']): r for r in csv.DictReader(f)}
    return rows, json.loads((out / 'summary.json').read_text()), out


def test_record_number_is_the_last_number_of_the_name():
    assert cwru_records.record_number('105.mat') == 105
    assert cwru_records.record_number('12k_Drive_End_OR007@6_0_130.mat') == 130
    assert cwru_records.record_number('12k_Drive_End_B014_2_187.mat') == 187
    assert cwru_records.record_number('48k_Drive_End_B007_0_122.mat') == 122
    assert cwru_records.record_number('normal_0_97.mat') == 97
    assert cwru_records.record_number('README.mat') is None
    assert cwru_records.name_rate_hz('48k_Drive_End_B007_0_122.mat') == 48000.0
    assert cwru_records.name_rate_hz('105.mat') is None


def test_tables():
    table = cwru_records.metadata()
    assert len(table) == 161 and 157 not in table and 216 not in table
    assert sum(row['channel'] == 'FE' for row in table.values()) == 45
    assert {k: table[310][k] for k in ('channel', 'fault', 'size_in', 'position', 'load_hp', 'nominal_rpm')} == {
        'channel': 'FE', 'fault': 'outer race', 'size_in': 0.014, 'position': '@3', 'load_hp': 0, 'nominal_rpm': 1797.0}
    assert {k: table[130][k] for k in ('sample_rate_hz', 'channel', 'fault', 'size_in', 'position', 'load_hp')} == {
        'sample_rate_hz': 12000.0, 'channel': 'DE', 'fault': 'outer race', 'size_in': 0.007, 'position': '@6',
        'load_hp': 0}
    assert (table[97]['fault'], table[97]['sample_rate_hz'], table[100]['nominal_rpm']) == ('none', 48000.0, 1730.0)
    assert (table[217]['sample_rate_hz'], table[217]['size_in'], table[217]['load_hp']) == (48000.0, 0.021, 3)
    assert (table[3004]['bearing'], table[3004]['nominal_rpm']) == ('NTN', 1730.0)
    grades = cwru_records.smith_randall()
    assert len(grades) == 52
    assert all(table[r]['sample_rate_hz'] == 12000.0 and table[r]['bearing'] == 'SKF' for r in grades)
    assert all(g['group'] == g['best'][0] for g in grades.values())
    assert grades[171] == {'m1': 'P1', 'm2': 'Y2', 'm3': 'Y2', 'best': 'Y2', 'group': 'Y'}


def test_a_wrong_rate_prefix_is_a_warning():
    meta = cwru_records.metadata()[130]
    assert '48 kHz' in cwru_records.rate_warning('48k_Drive_End_OR007@6_0_130.mat', meta)
    assert cwru_records.rate_warning('12k_Drive_End_OR007@6_0_130.mat', meta) == ''


def test_a_file_named_after_another_record_is_read(tmp_path):
    # As CWRU's 3005.mat, which holds X048_DE_time and no RPM.
    scipy.io.savemat(tmp_path / '3005.mat', {'X048_DE_time': np.ones((5, 1))})
    r = cwru_records.load_record(tmp_path / '3005.mat', cwru_records.metadata()[3005])
    assert r['variable'] == 'X048_DE_time' and r['signal'] == pytest.approx(np.full(5, G))
    assert (r['rpm'], r['rpm_source']) == (1797.0, 'table') and 'X3005_DE_time' in r['notes'][0]


def test_scoring_rules():
    def verdict(outcome, *kinds):
        return {'outcome': outcome, 'kinds': list(kinds), 'text': ''}
    assert cwru_scoring.score('outer race', verdict('fault', 'outer race')) == {
        'class': 'outer', 'right_alone': 1, 'wrong_named': 0, 'cannot_tell': ''}
    assert cwru_scoring.score('ball', verdict('fault', 'ball', 'cage')) == {
        'class': 'multiple', 'right_alone': 0, 'wrong_named': 1, 'cannot_tell': ''}
    assert cwru_scoring.score('ball', verdict('fault', 'inner race')) == {
        'class': 'inner', 'right_alone': 0, 'wrong_named': 1, 'cannot_tell': ''}
    assert cwru_scoring.score('ball', verdict('ambiguous', 'inner race', 'ball')) == {
        'class': 'ambiguous(inner|ball)', 'right_alone': 0, 'wrong_named': 0, 'cannot_tell': 'truth among'}
    assert cwru_scoring.score('outer race', verdict('ambiguous', 'inner race', 'ball'))['cannot_tell'] == \
        'truth not among'
    assert cwru_scoring.score('none', verdict('none')) == {
        'class': 'none', 'right_alone': 1, 'wrong_named': 0, 'cannot_tell': ''}
    assert cwru_scoring.score('none', verdict('fault', 'cage'))['wrong_named'] == 1
    with pytest.raises(ValueError):
        cwru_scoring.classify(verdict('maybe', 'ball'))


def test_verdict_given_or_derived():
    faults = [{'fault': 'outer race', 'suspected': True}, {'fault': 'cage', 'suspected': False}]
    assert cwru_scoring.verdict_of({'faults': faults})['kinds'] == ['outer race']
    given = {'outcome': 'ambiguous', 'kinds': ['inner race', 'ball'], 'text': 'cannot tell'}
    v = cwru_scoring.verdict_of({'faults': faults, 'verdict': given})
    assert (v['outcome'], v['kinds'], v['source']) == ('ambiguous', ['inner race', 'ball'], 'analyser')


def test_the_rules_are_in_the_help():
    assert cwru_scoring.RULES in cwru_benchmark.parser().format_help()


def test_normal_record_is_none_at_the_table_speed(run):
    rows, _, _ = run
    r = rows[97]
    assert (r['sample_rate_hz'], r['rpm'], r['rpm_source']) == ('48000', '1797.0', 'table')
    assert r['variable'] == 'X097_DE_time'  # the record number zero-padded
    assert (r['class'], r['right_alone'], r['wrong_named'], r['error']) == ('none', '1', '0', '')


def test_outer_race_train_is_outer_alone(run):
    rows, _, _ = run
    r = rows[130]
    assert (r['rpm'], r['rpm_source'], r['smith_randall_best']) == ('1797.0', 'file', 'Y1')
    assert (r['class'], r['right_alone'], r['wrong_named'], r['BPFO_suspected']) == ('outer', '1', '0', '1')
    assert float(r['BPFO_h1_snr_db']) > 20.0


def test_fan_end_record_is_read_from_its_own_channel_with_its_own_bearing(run):
    rows, _, _ = run
    r = rows[294]
    assert (r['channel'], r['variable'], r['rpm_source'], r['smith_randall_best']) == ('FE', 'X294_FE_time', 'file', '')
    assert (r['class'], r['right_alone'], r['BPFO_suspected']) == ('outer', '1', '1')
    assert float(r['BPFO_h1_snr_db']) > 20.0


def test_counts_and_confusion(run):
    rows, summary, out = run
    assert rows[131]['error'] and not rows[131]['class']  # the bad file: an error row
    assert 999 not in rows and summary['skipped_files'][0]['file'] == '12k_Drive_End_XX_999.mat'
    m = summary['confusion']
    cell = {(t, c): n for t, counts in zip(m['rows'], m['counts']) for c, n in zip(m['columns'], counts)}
    assert cell[('outer', 'outer')] == 2 and cell[('none', 'none')] == 1 and sum(cell.values()) == 3
    fan_end = summary['fan_end']['all']
    assert (fan_end['records'], fan_end['right_alone']) == (1, 1)
    graded = summary['graded_skf']['all']
    assert (graded['records'], graded['right_alone'], graded['errors']) == (2, 1, 1)  # 130, and 131 in error
    assert summary['smith_randall_groups']['Y']['right_alone'] == 1
    assert '#### Confusion matrix' in (out / 'summary.md').read_text()


def test_exit_2_without_records(tmp_path):
    r = subprocess.run([sys.executable, '-m', 'bearing_sim.cwru_benchmark', str(tmp_path), '--out',
                        str(tmp_path / 'out')], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=60)
    assert r.returncode == 2 and 'no .mat file' in r.stderr
    assert cwru_benchmark.main([str(tmp_path / 'missing'), '--out', str(tmp_path / 'out')]) == 2
