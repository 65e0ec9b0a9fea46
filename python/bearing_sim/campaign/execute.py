"""Runs of a campaign: one run as a pure function of (campaign, index) that writes its own
files, and the campaign on Dask distributed (a LocalCluster, or a scheduler's address) or
serially in this process (reference runs, or one task of a job array)."""
import itertools
import logging
import os
import shutil
import socket
import sys
import tempfile
import time
import uuid

import bearing_sim
from bearing_sim import _core

from .errors import CampaignError, OutputError
from .run_files import encode_hdf5, encode_npy, run_labels
from .run_lock import RunLock
from .spec import Campaign
from .store import RunStore, write_atomically

# Runs loaded (not run) before the campaign starts, until one loads: when none does, the
# template or its parameter ranges are wrong and the campaign is refused (docs/datasets.md).
TEMPLATE_CHECK_RUNS = 100
# Runs handed to Dask at a time per worker: enough to keep every worker busy, while the
# driver holds the futures of a window, not of the whole campaign.
RUNS_IN_FLIGHT_PER_WORKER = 4

_campaigns = {}  # per worker process: parsed once per (file, text)


def _campaign(path, text):
    key = (path, text)
    if key not in _campaigns:
        _campaigns[key] = Campaign(text, path)
    return _campaigns[key]


def scenario_text(campaign, run, work_dir):
    """The scenario of a run as YAML text and the source name it resolves against (the
    campaign's directory); derived bearing/sensor files are written into work_dir."""
    scenario = dict(run.scenario)
    for key, (file_name, text) in run.derived_files.items():
        path = os.path.join(work_dir, file_name)
        write_atomically(path, text.encode())
        scenario[key] = path
    source = os.path.join(campaign.directory, f'{os.path.basename(campaign.path)}, scenario of run {run.index}')
    return bearing_sim.yaml_text(scenario), source


def run_index(campaign_path, campaign_text, out_dir, index):
    """Runs run `index` and writes its data file and status record; never raises for a run
    that fails (the error is recorded), only an OutputError when out_dir cannot take the
    run's files. Returns the status record."""
    campaign = _campaign(campaign_path, campaign_text)
    store = RunStore(out_dir, campaign)
    store.remove_leftovers(index)
    # Dask runs a task again when the worker that holds its result dies before the driver has
    # fetched it (a node lost right after a run): that run is finished on disk, and is not
    # generated a second time. (The driver hands out only runs unfinished when it started, and
    # holds their lock, so a finished record here is this invocation's own.)
    finished = store.finished_record(index)
    if finished is not None:
        return finished
    start = time.perf_counter()
    record = {'index': index, 'campaign': campaign.name, 'host': socket.gethostname(), 'pid': os.getpid()}
    work_dir = os.path.join(store.runs_dir, f'.run_{index:07d}.{socket.gethostname()}.{os.getpid()}.tmp')
    try:
        run = campaign.definition(index)
        record['parameters'] = run.parameters
        record['seed'] = run.scenario['seed']
        try:
            os.makedirs(work_dir, exist_ok=True)
        except OSError as e:
            raise OutputError(f'cannot create {work_dir}: {e.strerror}') from None
        text, source = scenario_text(campaign, run, work_dir)
        result = _core.generate_from_yaml(text, source, None, None, float(campaign.label_rate_hz))
        data = encode_npy(result) if campaign.format == 'npy' else encode_hdf5(result, run.parameters)
        write_atomically(store.data_path(index), data)
        record.update(status='ok', file=os.path.relpath(store.data_path(index), store.out_dir), bytes=len(data),
                      labels=run_labels(result), simulated_s=result['info']['duration_s'], cpu_s=result['cpu_s'],
                      divergences=result['divergences'], simd_target=result['info']['simd_target'])
    except OutputError:  # not the run's fault: the campaign stops, the run is redone by a rerun
        raise
    except Exception as e:  # a failing run is recorded, never stops the campaign
        record.update(status='failed', error=f'{type(e).__name__}: {e}')
    finally:
        shutil.rmtree(work_dir, ignore_errors=True)
    record['wall_s'] = time.perf_counter() - start
    store.write_status(index, record)
    return record


def check_template(campaign, todo):
    """Loads the scenario, bearing and sensor of the runs to do, without running them, until one
    loads. If none of the first TEMPLATE_CHECK_RUNS does, the template (or the ranges of its
    parameters) is bad and the command stops before anything is dispatched; otherwise a run that
    fails on its own parameters is recorded when it runs, and the campaign goes on."""
    first_error, tried = None, 0
    for index in itertools.islice(todo, TEMPLATE_CHECK_RUNS):
        tried += 1
        try:
            run = campaign.definition(index)  # a CampaignError here may be the run's values too
            with tempfile.TemporaryDirectory() as work_dir:
                text, source = scenario_text(campaign, run, work_dir)
                _core.check_scenario(text, source)
            return
        except OutputError:
            raise
        except (CampaignError, bearing_sim.ConfigError, bearing_sim.InvalidInputError) as e:
            first_error = first_error or f'run {index}: {e}'
    raise CampaignError(f"{campaign.path}: key 'scenario': none of the first {tried} run(s) to do loads "
                        f'(a template error, or parameter ranges no run can satisfy); {first_error}')


def parse_index_range(text, count):
    """'A:B' -> range(A, B), half-open as in Python; checked against the campaign's count."""
    try:
        a, b = (int(x) for x in text.split(':'))
    except ValueError:
        raise CampaignError(f"--index-range: expected A:B (runs A to B-1), got '{text}'") from None
    if not 0 <= a < b <= count:
        raise CampaignError(f"--index-range {text}: expected 0 <= A < B <= {count} (the campaign's count)")
    return range(a, b)


def run_campaign(campaign, out_dir, indices=None, client=None, scheduler=None, workers=None, serial=False,
                 log=lambda line: print(line, file=sys.stderr)):
    """Runs the unfinished runs among `indices` (a range, default all) and rebuilds the manifest.
    Holds the runs' lock in out_dir meanwhile (run_lock.py). An OutputError (a full disk) stops
    the campaign after the manifest of what is finished. Returns {'requested', 'skipped', 'ok',
    'failed'}."""
    store = RunStore(out_dir, campaign)
    store.prepare()
    indices = range(campaign.count) if indices is None else indices
    with RunLock(store.out_dir, indices):
        finished = store.finished(indices)
        skipped = finished.count(1)
        summary = {'requested': len(indices), 'skipped': skipped, 'ok': 0, 'failed': 0}

        def todo():  # one index at a time: a campaign's count is not held in memory
            return (indices.start + k for k in range(len(indices)) if not finished[k])
        log(f'campaign {campaign.name}: {len(indices) - skipped} run(s) to do, {skipped} already finished')
        if skipped < len(indices):
            check_template(campaign, todo())

        def done(record):
            summary['ok' if record['status'] == 'ok' else 'failed'] += 1
            if record['status'] != 'ok':
                log(f"campaign {campaign.name}: run {record['index']} failed: {record.get('error')}")

        args = (campaign.path, campaign.text, store.out_dir)
        try:
            if serial or skipped == len(indices):
                for i in todo():
                    done(run_index(*args, i))
            else:
                _run_on_dask(args, todo(), client, scheduler, workers, store, done)
        except OutputError as e:
            raise OutputError(f'{e}; the campaign stopped ({summary["ok"]} run(s) finished now, '
                              f'{_manifest_after_error(store)}); free space or fix the directory and run it '
                              f'again to resume') from None
        store.write_manifest()
    log(f"campaign {campaign.name}: {summary['ok']} finished, {summary['failed']} failed, "
        f"{summary['skipped']} skipped (finished before); manifest {os.path.join(store.out_dir, 'manifest.csv')}")
    return summary


def _manifest_after_error(store):
    try:
        store.write_manifest()
        return f"manifest {os.path.join(store.out_dir, 'manifest.csv')}"
    except OutputError as e:
        return f'no manifest either: {e}'


def _run_on_dask(args, todo, client, scheduler, workers, store, done):
    from dask.distributed import Client, LocalCluster, as_completed
    own = []
    try:
        if client is None:
            if scheduler:
                client = Client(scheduler, timeout='30s')
            else:
                n = workers or len(os.sched_getaffinity(0))
                # One single-threaded process per core: a crashing run takes only its worker.
                cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                       dashboard_address=None, silence_logs=logging.ERROR)
                own.append(cluster)
                client = Client(cluster)
            own.insert(0, client)
        token = uuid.uuid4().hex[:8]
        in_flight = {}  # key -> (future, index)
        running = as_completed()

        def workers_now():  # an adaptive cluster grows: counted again every few seconds
            return max(1, len(client.scheduler_info()['workers']))

        def top_up():
            while len(in_flight) < RUNS_IN_FLIGHT_PER_WORKER * n_workers:
                i = next(todo, None)
                if i is None:
                    return
                future = client.submit(run_index, *args, i, pure=False, key=f'bearing-campaign-{token}-run-{i}')
                in_flight[future.key] = (future, i)
                running.add(future)

        n_workers, counted = workers_now(), time.monotonic()
        top_up()
        try:
            for future in running:
                _, i = in_flight.pop(future.key)
                try:
                    record = future.result()
                except OutputError:
                    raise
                except Exception as e:  # the worker died (after the scheduler's retries) or was lost
                    record = {'index': i, 'status': 'failed', 'error': f'{type(e).__name__}: {e}'}
                    if store.is_finished(i):
                        record = store.read_status(i)
                    else:
                        store.write_status(i, record)
                done(record)
                future.release()
                if time.monotonic() - counted > 5.0:
                    n_workers, counted = workers_now(), time.monotonic()
                top_up()
        except OutputError:
            for future, _ in in_flight.values():
                future.cancel()
            raise
    finally:
        for thing in own:
            thing.close()
