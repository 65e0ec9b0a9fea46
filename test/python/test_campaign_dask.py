"""Campaigns on Dask distributed: a LocalCluster of 2 workers gives the same bytes as a
serial run; a worker killed mid-campaign loses nothing (the rerun completes it); partial
files never count; a failing run is recorded and the others go on, also when the first
runs fail; a template no run loads is refused."""
import csv
import os
import signal
import threading
import time

import pytest
from dask.distributed import Client, LocalCluster

from bearing_sim.campaign import Campaign, CampaignError, run_campaign
from bearing_sim.campaign.execute import TEMPLATE_CHECK_RUNS
from bearing_sim.campaign.store import RunStore
from conftest import small_campaign


@pytest.fixture(scope='module')
def client():
    import logging
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                           silence_logs=logging.CRITICAL)
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()


def files(out):
    return {p.name: p.read_bytes() for p in sorted((out / 'runs').glob('run_*.npy'))}


def manifest(out):
    with open(out / 'manifest.csv', newline='') as f:
        return list(csv.DictReader(f))


def quiet(line):
    pass


def test_two_workers_give_the_bytes_of_a_serial_run(client, campaign_file, tmp_path):
    c = Campaign.load(campaign_file(small_campaign(count=20)))
    s = run_campaign(c, tmp_path / 'serial', serial=True, log=quiet)
    d = run_campaign(c, tmp_path / 'dask', client=client, log=quiet)
    assert s['ok'] == d['ok'] == 20 and s['failed'] == d['failed'] == 0
    serial, dask = files(tmp_path / 'serial'), files(tmp_path / 'dask')
    assert len(serial) == 20 and serial == dask
    records = list(RunStore(tmp_path / 'dask', c).records())
    # Both workers took part: no run order or placement enters the bytes.
    assert len({r['pid'] for r in records}) == 2
    # Every record names the SIMD target its kernels ran on (the bytes hold for one target).
    import bearing_sim
    assert {r['simd_target'] for r in records} == {bearing_sim.simd_target_name()}
    rows = manifest(tmp_path / 'dask')
    assert [int(r['index']) for r in rows] == list(range(20)) and {r['status'] for r in rows} == {'ok'}
    assert {r['label_defects_at_end'] for r in rows} == {'none', 'outer_race'}
    # A rerun skips everything.
    again = run_campaign(c, tmp_path / 'dask', client=client, log=quiet)
    assert again['skipped'] == 20 and again['ok'] == 0


def test_hdf5_runs_are_reproducible(campaign_file, tmp_path):
    import h5py
    import numpy as np
    c = Campaign.load(campaign_file(small_campaign(count=2, fmt='hdf5')))
    run_campaign(c, tmp_path / 'a', serial=True, log=quiet)
    time.sleep(1.1)  # a creation time in the file would now differ
    run_campaign(c, tmp_path / 'b', serial=True, log=quiet)
    for i in range(2):
        a = (tmp_path / 'a' / 'runs' / f'run_{i:07d}.h5').read_bytes()
        assert a == (tmp_path / 'b' / 'runs' / f'run_{i:07d}.h5').read_bytes()
    with h5py.File(tmp_path / 'a' / 'runs' / 'run_0000001.h5') as f:
        assert f['vibration'].shape == (2000, 3) and f['vibration'].dtype == np.float32
        assert f['label_time_s'][:] == pytest.approx([0.0, 0.1])


def test_a_killed_worker_loses_nothing(client, campaign_file, tmp_path):
    # Runs of 5 s simulated (~0.1 s of CPU each): the kill lands inside one.
    c = Campaign.load(campaign_file(small_campaign(count=12, duration_s=5.0)))
    out = tmp_path / 'killed'
    killed = {}

    def kill_a_busy_worker():
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not list((out / 'runs').glob('run_*.json')):
            time.sleep(0.01)
        busy = [w for w, keys in client.processing().items() if keys]
        if not busy:
            return
        killed['pid'] = client.run(os.getpid, workers=[busy[0]])[busy[0]]
        killed['runs'] = len(list((out / 'runs').glob('run_*.json')))
        os.kill(killed['pid'], signal.SIGKILL)
    t = threading.Thread(target=kill_a_busy_worker)
    t.start()
    first = run_campaign(c, out, client=client, log=quiet)
    t.join()
    assert killed and killed['runs'] < 12, 'the worker was not killed while runs were left'
    # Dask reruns what the dead worker held, or the run is recorded as failed; either way
    # the rerun leaves every run finished, with the bytes of a serial run.
    second = run_campaign(c, out, client=client, log=quiet)
    assert first['ok'] + second['ok'] == 12 and second['failed'] == 0
    run_campaign(c, tmp_path / 'serial', serial=True, log=quiet)
    assert files(out) == files(tmp_path / 'serial')
    assert {r['status'] for r in manifest(out)} == {'ok'}
    client.wait_for_workers(2, timeout=60)  # the nanny restarted the killed worker


def test_partial_files_never_count(campaign_file, tmp_path):
    c = Campaign.load(campaign_file(small_campaign(count=4)))
    out = tmp_path / 'partial'
    run_campaign(c, out, serial=True, log=quiet)
    reference = files(out)
    runs = out / 'runs'
    # Run 1 cut short after its record was written, run 2's record lost, run 3 left as a
    # temporary file by a killed writer: none of them is finished.
    data = (runs / 'run_0000001.npy').read_bytes()
    (runs / 'run_0000001.npy').write_bytes(data[:len(data) // 2])
    (runs / 'run_0000002.json').unlink()
    (runs / 'run_0000003.npy').rename(runs / '.run_0000003.npy.host.123.tmp')
    again = run_campaign(c, out, serial=True, log=quiet)
    assert again['skipped'] == 1 and again['ok'] == 3
    assert files(out) == reference
    assert not list(runs.glob('.*.tmp'))


def test_a_failing_run_is_recorded_and_the_others_go_on(campaign_file, tmp_path):
    doc = small_campaign(count=10)
    # A 60 mm spall cannot fit a 6205 outer raceway (a quarter of it is 37 mm): those runs fail.
    doc['parameters']['width_mm'] = {'choice': [0.5, 60.0]}
    doc['parameters']['defects'] = {'choice': [[{'type': 'spall', 'at_s': 0.05, 'surface': 'outer_race',
                                                 'position_deg': 0.0, 'width_mm': '${width_mm}',
                                                 'depth_um': 10.0}]]}
    c = Campaign.load(campaign_file(doc))
    wide = [i for i in range(10) if c.parameters_of(i)['width_mm'] == 60.0]
    assert 0 < len(wide) < 10
    out = tmp_path / 'failing'
    s = run_campaign(c, out, serial=True, log=quiet)
    assert s['failed'] == len(wide) and s['ok'] == 10 - len(wide)
    rows = {int(r['index']): r for r in manifest(out)}
    for i in range(10):
        if i in wide:
            assert rows[i]['status'] == 'failed' and 'defects[0]' in rows[i]['error'] and rows[i]['file'] == ''
            assert not (out / 'runs' / f'run_{i:07d}.npy').exists()
        else:
            assert rows[i]['status'] == 'ok' and (out / rows[i]['file']).is_file()


def spall_campaign(widths_mm, count, seed):
    doc = small_campaign(count=count, seed=seed)
    doc['parameters']['width_mm'] = {'choice': widths_mm}
    doc['parameters']['defects'] = {'choice': [[{'type': 'spall', 'at_s': 0.05, 'surface': 'outer_race',
                                                 'position_deg': 0.0, 'width_mm': '${width_mm}',
                                                 'depth_um': 10.0}]]}
    return doc


def test_runs_that_fail_first_are_recorded_and_the_campaign_goes_on(campaign_file, tmp_path):
    # A 1000 mm spall cannot fit a 6205 (a quarter of its outer raceway is 36.9 mm). The seed
    # is the first whose runs 0-2 draw it and run 3 does not.
    for seed in range(1000):
        c = Campaign.load(campaign_file(spall_campaign([1000.0, 0.5], 6, seed)))
        wide = [c.parameters_of(i)['width_mm'] == 1000.0 for i in range(6)]
        if wide[:4] == [True, True, True, False]:
            break
    else:
        pytest.fail('no seed draws the spall widths wanted')
    s = run_campaign(c, tmp_path / 'out', serial=True, log=quiet)
    assert (s['ok'], s['failed']) == (wide.count(False), wide.count(True))
    rows = {int(r['index']): r for r in manifest(tmp_path / 'out')}
    for i in range(6):
        if wide[i]:
            assert rows[i]['status'] == 'failed' and 'at most a quarter of the raceway (36.898006 mm)' in rows[i]['error']
        else:
            assert rows[i]['status'] == 'ok'


def test_a_template_none_of_the_first_runs_loads_is_refused(campaign_file, tmp_path):
    c = Campaign.load(campaign_file(spall_campaign([1000.0, 2000.0], TEMPLATE_CHECK_RUNS + 5, 1)))
    with pytest.raises(CampaignError) as e:
        run_campaign(c, tmp_path / 'out', serial=True, log=quiet)
    assert f"key 'scenario': none of the first {TEMPLATE_CHECK_RUNS} run(s) to do loads" in str(e.value)
    assert 'run 0: ' in str(e.value) and 'at most a quarter of the raceway' in str(e.value)
    assert not list((tmp_path / 'out' / 'runs').glob('run_*'))


def test_a_run_whose_text_draws_a_list_is_recorded_and_the_campaign_goes_on(campaign_file, tmp_path):
    # A list cannot be part of a text: the runs that draw it fail on their values, run 0 among them.
    for seed in range(1000):
        doc = small_campaign(count=6, seed=seed)
        doc['parameters']['tag'] = {'choice': [[1, 2], 'a']}
        doc['scenario']['description'] = 'tag ${tag}'
        c = Campaign.load(campaign_file(doc))
        listed = [isinstance(c.parameters_of(i)['tag'], list) for i in range(6)]
        if listed[0] and not all(listed):
            break
    else:
        pytest.fail('no seed draws the tags wanted')
    s = run_campaign(c, tmp_path / 'out', serial=True, log=quiet)
    assert (s['ok'], s['failed']) == (listed.count(False), listed.count(True))
    rows = {int(r['index']): r for r in manifest(tmp_path / 'out')}
    for i in range(6):
        assert rows[i]['status'] == ('failed' if listed[i] else 'ok')
        if listed[i]:
            assert '${tag} is a list or mapping and cannot be part of a text' in rows[i]['error']


def test_a_finished_run_handed_out_again_is_not_generated_again(campaign_file, tmp_path):
    # Dask computes a task again when the worker holding its result dies before the driver
    # fetched it: run_index then finds the run finished and returns its record untouched.
    from bearing_sim.campaign.execute import run_index
    c = Campaign.load(campaign_file(small_campaign(count=2)))
    out = tmp_path / 'again'
    RunStore(out, c).prepare()
    first = run_index(c.path, c.text, str(out), 1)
    data = out / 'runs' / 'run_0000001.npy'
    record = (out / 'runs' / 'run_0000001.json').read_bytes()
    stamp = data.stat().st_mtime_ns
    assert run_index(c.path, c.text, str(out), 1) == first
    assert (out / 'runs' / 'run_0000001.json').read_bytes() == record and data.stat().st_mtime_ns == stamp
    # A run whose data file was cut is not finished: it is generated again, to the same bytes.
    full = data.read_bytes()
    data.write_bytes(full[:100])
    assert run_index(c.path, c.text, str(out), 1)['status'] == 'ok' and data.read_bytes() == full
