"""Campaign files: the distributions (statistics against their definitions), run i as a
function of (campaign, i) alone, and errors that name the key."""
import math
import os
import subprocess
import sys

import numpy as np
import pytest
import yaml

from bearing_sim.campaign import Campaign, CampaignError
from conftest import BEARINGS, SOURCE, small_campaign


# Not a file: its directory is where the shipped campaigns find ../bearings.
IN_CONFIG = str(SOURCE / 'config' / 'campaigns' / 'c.yaml')


def campaign(doc, path=IN_CONFIG):
    return Campaign(yaml.safe_dump(doc), path)


def draws(spec, n=4000, seed=3):
    c = campaign({'name': 'd', 'count': n, 'seed': seed, 'parameters': {'p': spec}, 'scenario': {'x': '${p}'}})
    return np.array([c.parameters_of(i)['p'] for i in range(n)])


def test_uniform_and_log_uniform_have_their_moments():
    n = 4000
    u = draws({'uniform': [2.0, 6.0]}, n)
    assert u.min() >= 2.0 and u.max() < 6.0
    # Mean 4, standard deviation 4/sqrt(12); 4 standard errors.
    assert abs(u.mean() - 4.0) < 4 * (4 / math.sqrt(12)) / math.sqrt(n)
    lu = draws({'log_uniform': [1e-3, 1e1]}, n)
    logs = np.log(lu)
    assert lu.min() >= 1e-3 and lu.max() < 1e1
    span = math.log(1e4)
    assert abs(logs.mean() - (math.log(1e-3) + span / 2)) < 4 * (span / math.sqrt(12)) / math.sqrt(n)


def test_bounded_normal_and_choice_and_integer():
    n = 4000
    x = draws({'normal': {'mean': 10.0, 'std': 2.0, 'min': 9.0, 'max': 20.0}}, n)
    assert x.min() >= 9.0 and x.max() <= 20.0
    # Truncated normal mean: mu + sigma (phi(a) - phi(b)) / (Phi(b) - Phi(a)), a = -0.5, b = 5.
    phi = lambda z: math.exp(-z * z / 2) / math.sqrt(2 * math.pi)  # noqa: E731
    Phi = lambda z: 0.5 * (1 + math.erf(z / math.sqrt(2)))  # noqa: E731
    expected = 10.0 + 2.0 * (phi(-0.5) - phi(5.0)) / (Phi(5.0) - Phi(-0.5))
    assert abs(x.mean() - expected) < 4 * 2.0 / math.sqrt(n)
    c = draws({'choice': ['a', 'b', 'c', 'd']}, n)
    for v in 'abcd':  # binomial, p = 1/4
        assert abs(np.mean(c == v) - 0.25) < 4 * math.sqrt(0.25 * 0.75 / n)
    k = draws({'integer': [3, 5]}, n)
    assert set(k.tolist()) == {3, 4, 5}


def test_grid_enumerates_the_cartesian_product():
    c = campaign({'name': 'g', 'count': 12, 'parameters': {'a': {'grid': [1, 2, 3]}, 'b': {'grid': ['x', 'y']}},
                  'scenario': {'x': '${a}${b}'}})
    combos = [(c.parameters_of(i)['a'], c.parameters_of(i)['b']) for i in range(12)]
    assert combos[:6] == [(1, 'x'), (1, 'y'), (2, 'x'), (2, 'y'), (3, 'x'), (3, 'y')]
    assert combos[6:] == combos[:6]
    assert c.definition(3).scenario['x'] == '2y'


def test_run_i_depends_on_campaign_and_i_alone():
    doc = small_campaign(count=50)
    a = campaign(doc)
    bigger = dict(doc, count=5000)
    more = dict(doc, parameters=dict(doc['parameters'], extra={'uniform': [0.0, 1.0]}))
    for i in (0, 7, 49):
        pa = a.parameters_of(i)
        assert campaign(bigger).parameters_of(i) == pa
        pm = campaign(more).parameters_of(i)
        assert {k: pm[k] for k in pa} == pa
        assert a.definition(i).scenario['seed'] == campaign(bigger).definition(i).scenario['seed']
    other_seed = campaign(dict(doc, seed=12))
    assert other_seed.parameters_of(7) != a.parameters_of(7)


def test_template_substitution_keeps_types_and_nests():
    c = campaign(small_campaign(count=4))
    found = set()
    for i in range(4):
        s = c.definition(i).scenario
        assert isinstance(s['speed']['initial_speed_rpm'], float)
        assert s['name'] == f'small_{i:07d}'
        if s['defects']:
            d = s['defects'][0]
            assert d['width_mm'] in (0.5, 1.0) and d['position_deg'] in (0.0, 120.0)
            found.add('spall')
        else:
            found.add('none')


def _set(key, value):
    return lambda d: d.update({key: value})


def _param(spec):
    return lambda d: d['parameters'].update(v=spec)


BAD = [
    (lambda d: d.pop('name'), "key 'name': required"),
    (_set('cuont', 3), "key 'cuont': unknown key"),
    (_set('count', 0), "key 'count': must be 1 to 10,000,000"),
    (_set('count', 'many'), "key 'count': expected int"),
    (_set('format', 'parquet'), "key 'format': expected one of npy, hdf5"),
    (_set('seed', -4), "key 'seed'"),
    (_param({'uniform': [5.0, 1.0]}), "key 'parameters.v.uniform': expected low < high"),
    (_param({'uniform': [1.0]}), "key 'parameters.v.uniform'"),
    (_param({'log_uniform': [0.0, 1.0]}), "key 'parameters.v.log_uniform': a log-uniform range"),
    (_param({'normal': {'mean': 1.0}}), "key 'parameters.v.normal'"),
    (_param({'normal': {'mean': 1.0, 'std': -1.0}}), "key 'parameters.v.normal.std'"),
    (_param({'gaussian': [1, 2]}), "key 'parameters.v': expected a value or one of"),
    (_param({'choice': []}), "key 'parameters.v.choice'"),
    (lambda d: d['scenario'].update(duration_s='${nope}'), "key 'scenario.duration_s': unknown parameter ${nope}"),
    (lambda d: d.pop('scenario'), "key 'scenario': required"),
]


@pytest.mark.parametrize('change, message', BAD)
def test_bad_campaign_files_name_the_key(change, message):
    doc = small_campaign()
    change(doc)
    with pytest.raises(CampaignError) as e:
        campaign(doc)
    assert message in str(e.value)
    assert IN_CONFIG in str(e.value)


def test_bad_scenario_template_is_refused_before_running(campaign_file, tmp_path):
    doc = small_campaign()
    doc['scenario']['speed'] = {'initial_speed_rpm': '${speed_rpm}', 'segments': [{'type': 'warp', 'start_s': 0.0}]}
    path = campaign_file(doc)
    script = SOURCE / 'scripts' / 'bearing_campaign'
    r = subprocess.run([sys.executable, str(script), str(path), '--out', str(tmp_path / 'out'), '--serial'],
                       capture_output=True, text=True, timeout=60, env=os.environ)
    assert r.returncode == 2, r.stderr
    # Every run fails alike: all 20 (fewer than TEMPLATE_CHECK_RUNS) are tried, the first error named.
    assert "key 'scenario': none of the first 20 run(s) to do loads" in r.stderr, r.stderr
    assert 'run 0: ' in r.stderr and 'speed.segments[0]' in r.stderr
    assert not (tmp_path / 'out' / 'runs').exists() or not list((tmp_path / 'out' / 'runs').glob('run_*'))
    for args, message in ((['--index-range', '5:2'], '--index-range 5:2'),
                          (['--index-range', '0:21'], 'expected 0 <= A < B <= 20'),
                          (['--workers', '0'], '--workers')):
        r = subprocess.run([sys.executable, str(script), str(campaign_file(small_campaign(), 'ok.yaml')),
                            '--out', str(tmp_path / 'out2')] + args, capture_output=True, text=True, timeout=60)
        assert r.returncode == 2 and message in r.stderr, r.stderr


def test_a_key_written_twice_is_refused_naming_file_key_and_lines(campaign_file, tmp_path):
    # PyYAML keeps the last occurrence silently; a campaign file is read as the core reads its files.
    text = yaml.safe_dump(small_campaign(), sort_keys=False).replace('count: 20\n', 'count: 20\ncount: 2\n', 1)
    path = campaign_file(text, 'twice.yaml')
    with pytest.raises(CampaignError) as e:
        Campaign.load(str(path))
    assert str(path) in str(e.value) and "key 'count' appears twice (lines 2 and 3)" in str(e.value)
    # A bearing file derived with {file: ..., set: ...} is parsed here before the core sees it.
    bearing = tmp_path / 'twice_bearing.yaml'
    bearing.write_text((BEARINGS / 'deep_groove_6205.yaml').read_text() + 'balls_per_row: 10\n')
    doc = small_campaign()
    doc['scenario']['bearing_file'] = {'file': str(bearing), 'set': {'imperfections.roughness_rms_um': 0.1}}
    with pytest.raises(CampaignError) as e:
        campaign(doc).definition(0)
    assert str(bearing) in str(e.value) and "key 'balls_per_row' appears twice" in str(e.value)


@pytest.mark.parametrize('path', ['/dev/zero', '/tmp', '/nonexistent/campaign.yaml'])
def test_a_campaign_path_that_is_no_regular_file_is_refused_naming_it(path):
    with pytest.raises(CampaignError) as e:
        Campaign.load(path)
    assert path in str(e.value)
