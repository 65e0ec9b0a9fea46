"""Campaign files that would hang the command or exhaust memory are refused before anything
runs, naming the key, the value and its limit (exit 2): a count beyond the 7-digit run names,
references that multiply, references in a circle, a YAML alias bomb. A large count starts
its first run without visiting every index first. The refusals run in a child process with
its address space capped, so that a regression fails instead of swapping the machine."""
import os
import resource
import subprocess
import sys
import tracemalloc

import pytest
import yaml

import bearing_sim.campaign.execute as execute
from bearing_sim.campaign import Campaign, CampaignError, run_campaign
from bearing_sim.campaign.spec import MAX_COUNT
from bearing_sim.campaign.store import RunStore
from conftest import SOURCE, small_campaign

SCRIPT = SOURCE / 'scripts' / 'bearing_campaign'
ADDRESS_SPACE = 1 << 30  # 1 GiB: the command needs < 100 MB to refuse a file


def capped():
    resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE, ADDRESS_SPACE))


def bearing_campaign(path, out, *args):
    env = dict(os.environ, OPENBLAS_NUM_THREADS='1', OMP_NUM_THREADS='1')
    return subprocess.run([sys.executable, str(SCRIPT), str(path), '--out', str(out), '--serial', *args],
                          capture_output=True, text=True, timeout=120, env=env, preexec_fn=capped)


def multiplying_references(levels=8, fan_out=10):
    """a0: ten numbers; a1: ten '${a0}'; ...: a(levels-1) holds 10^levels numbers once filled in."""
    parameters = {'a0': list(range(fan_out))}
    for k in range(1, levels):
        parameters[f'a{k}'] = [f'${{a{k - 1}}}'] * fan_out
    doc = small_campaign()
    doc['parameters'].update(parameters)
    doc['scenario']['description'] = f'${{a{levels - 1}}}'
    return doc


def test_a_count_beyond_the_run_names_is_refused_naming_the_limit(campaign_file, tmp_path):
    r = bearing_campaign(campaign_file(small_campaign(count=1000000000000)), tmp_path / 'out')
    assert r.returncode == 2, r.stderr
    assert "key 'count': must be 1 to 10,000,000" in r.stderr and 'got 1,000,000,000,000' in r.stderr
    assert not (tmp_path / 'out').exists()


def test_references_that_multiply_are_refused_naming_the_first_too_large(campaign_file, tmp_path):
    r = bearing_campaign(campaign_file(multiplying_references()), tmp_path / 'out')
    assert r.returncode == 2, r.stderr
    # a4 holds 10^5 numbers (~300 kB of YAML), a5 10^6: the first beyond 1 MiB.
    assert "key 'parameters.a5': with its ${...} filled in, the value can take" in r.stderr, r.stderr
    assert 'more than 1048576 (1 MiB, the size limit of a configuration file)' in r.stderr
    # Within the limit the same structure is accepted and filled in exactly.
    c = Campaign(yaml.safe_dump(multiplying_references(levels=3)), str(campaign_file(small_campaign())))
    assert c.definition(0).scenario['description'] == [[list(range(10))] * 10] * 10


def test_parameters_in_a_circle_are_refused_and_text_references_are_filled_in(campaign_file):
    path = str(campaign_file(small_campaign()))
    doc = small_campaign()
    doc['parameters'].update(a='x${b}', b='y${c}', c={'choice': ['${a}', 1]})
    doc['scenario']['description'] = '${a}'
    with pytest.raises(CampaignError) as e:
        Campaign(yaml.safe_dump(doc), path)
    assert "key 'parameters.c': parameters refer to each other in a circle: ${a} -> ${b} -> ${c} -> ${a}" \
        in str(e.value)
    # Without the circle, a reference inside a text is filled in at every depth: the manifest
    # and the scenario hold no literal ${...}.
    doc['parameters']['c'] = {'choice': ['z${d}']}
    doc['parameters']['d'] = 7
    run = Campaign(yaml.safe_dump(doc), path).definition(0)
    assert run.scenario['description'] == 'xyz7'
    assert (run.parameters['a'], run.parameters['b'], run.parameters['c']) == ('xyz7', 'yz7', 'z7')


ALIAS_BOMB = """name: bomb
count: 1
parameters:
  l0: &l0 [x, x, x, x, x, x, x, x, x, x]
  l1: &l1 [*l0, *l0, *l0, *l0, *l0, *l0, *l0, *l0, *l0, *l0]
  l2: &l2 [*l1, *l1, *l1, *l1, *l1, *l1, *l1, *l1, *l1, *l1]
  l3: &l3 [*l2, *l2, *l2, *l2, *l2, *l2, *l2, *l2, *l2, *l2]
  l4: &l4 [*l3, *l3, *l3, *l3, *l3, *l3, *l3, *l3, *l3, *l3]
  l5: &l5 [*l4, *l4, *l4, *l4, *l4, *l4, *l4, *l4, *l4, *l4]
  l6: &l6 [*l5, *l5, *l5, *l5, *l5, *l5, *l5, *l5, *l5, *l5]
  l7: &l7 [*l6, *l6, *l6, *l6, *l6, *l6, *l6, *l6, *l6, *l6]
  l8: &l8 [*l7, *l7, *l7, *l7, *l7, *l7, *l7, *l7, *l7, *l7]
scenario: {duration_s: 0.1, bearing_file: deep_groove_6205.yaml}
"""


@pytest.mark.parametrize('text, message', [
    (ALIAS_BOMB, 'refused: its aliases expand it to 2345679127 bytes, more than 1048576 (1 MiB, the size limit of a '
                 'configuration file)'),
    ('name: self\ncount: 1\nparameters: {a: &a [1, *a]}\nscenario: {}\n', 'refused: an alias contains itself'),
    ('name: deep\ncount: 1\nparameters: {a: ' + '[' * 5000 + ']' * 5000 + '}\n',
     'refused: lists or mappings nested too deeply to read'),
], ids=['alias bomb', 'alias in itself', 'nesting'])
def test_yaml_that_expands_or_nests_without_bound_is_refused(campaign_file, tmp_path, text, message):
    path = campaign_file(text, 'bomb.yaml')
    r = bearing_campaign(path, tmp_path / 'out')
    assert r.returncode == 2, r.stderr
    assert f'{path}: {message}' in r.stderr, r.stderr
    assert 'Traceback' not in r.stderr


def test_the_first_run_of_a_large_count_starts_without_visiting_every_index(campaign_file, tmp_path, monkeypatch):
    c = Campaign.load(campaign_file(small_campaign(count=MAX_COUNT)))
    started, lookups = [], []

    class Enough(Exception):
        pass

    def run_index(path, text, out, index):
        started.append(index)
        raise Enough()
    is_finished = RunStore.is_finished
    monkeypatch.setattr(execute, 'run_index', run_index)
    monkeypatch.setattr(RunStore, 'is_finished', lambda self, i: lookups.append(i) or is_finished(self, i))
    tracemalloc.start()
    try:
        with pytest.raises(Enough):
            run_campaign(c, tmp_path / 'out', serial=True, log=lambda line: None)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert started == [0] and lookups == []
    # One byte per index (10 MB) at most; a list of ten million indices would be 400 MB.
    assert peak < 32 << 20, peak


def test_an_empty_out_is_refused(campaign_file, tmp_path):
    r = subprocess.run([sys.executable, str(SCRIPT), str(campaign_file(small_campaign())), '--out', ''],
                       capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert r.returncode == 2 and '--out: empty' in r.stderr, r.stderr
    assert list(tmp_path.iterdir()) == [tmp_path / 'config']
