"""A campaign on a real Dask cluster of separate processes, as on a cluster's nodes (issue 34):
a `dask scheduler` and two `dask worker` processes (each with its nanny, --nthreads 1) on
localhost, on ports the OS chooses, and `bearing_campaign --scheduler tcp://...` runs of the
shipped config/campaigns/deep_groove_defects.yaml. Once the first run is recorded, one worker
is killed with its nanny (SIGKILL to its process group: a node that went away) while it is
inside a run. The one invocation still finishes every run, each exactly once, with the bytes
and the manifest of the same runs made --serial. The processes are stopped at the end, also
when the test fails. Nothing here asserts speed: every wait is on an event, with a generous
time-out."""
import contextlib
import csv
import json
import os
import pathlib
import re
import signal
import socket
import subprocess
import sys
import threading
import time

import pytest

from conftest import SOURCE

CAMPAIGN = SOURCE / 'config' / 'campaigns' / 'deep_groove_defects.yaml'
RUNS = 32  # runs 0..31 of the shipped campaign (--index-range 0:32), 1 s simulated each
TIMEOUT_S = 600  # any single wait; the whole test takes ~20-60 s on 2 shared cores


def campaign_command():
    """bearing_campaign of the devel space this test runs against (its relay script)."""
    for prefix in os.environ.get('CMAKE_PREFIX_PATH', '').split(os.pathsep):
        candidate = pathlib.Path(prefix) / 'lib' / 'bearing_sim' / 'bearing_campaign'
        if candidate.is_file():
            return [sys.executable, str(candidate)]
    raise RuntimeError('bearing_campaign not found under CMAKE_PREFIX_PATH: source the devel space first')


def wait_for(what, condition, timeout=TIMEOUT_S, processes=()):
    deadline = time.monotonic() + timeout
    while not condition():
        for p in processes:
            if p.poll() is not None:
                raise AssertionError(f'{what}: {p.args[:3]} exited with {p.returncode} first')
        if time.monotonic() > deadline:
            raise AssertionError(f'{what}: not within {timeout} s')
        time.sleep(0.01)


class DaskProcesses:
    """A scheduler and workers as separate process groups; stop() ends them all."""

    def __init__(self, directory):
        self.directory = directory
        self.scheduler_file = directory / 'scheduler.json'
        self.procs = {}

    def _start(self, name, args):
        log = open(self.directory / f'{name}.log', 'wb')
        # A process group of its own: a worker's nanny and its worker process die together.
        self.procs[name] = subprocess.Popen(['/usr/bin/dask'] + args, stdout=log, stderr=subprocess.STDOUT,
                                            cwd=self.directory, start_new_session=True)
        log.close()
        return self.procs[name]

    def start(self, workers):
        # Port 0: the OS picks a free port; the scheduler file tells it to the workers and to us.
        self._start('scheduler', ['scheduler', '--host', '127.0.0.1', '--port', '0', '--no-dashboard', '--no-show',
                                  '--scheduler-file', str(self.scheduler_file), '--idle-timeout', '1h'])
        wait_for('the scheduler file', lambda: self._address() is not None, processes=[self.procs['scheduler']])
        for k in range(workers):
            self._start(f'worker{k}', ['worker', '--scheduler-file', str(self.scheduler_file), '--host', '127.0.0.1',
                                       '--nthreads', '1', '--nworkers', '1', '--name', f'worker{k}', '--no-dashboard',
                                       '--local-directory', str(self.directory / f'worker{k}'),
                                       # the worker ends itself if the scheduler is gone for this long
                                       '--death-timeout', '120'])
        from dask.distributed import Client
        with Client(scheduler_file=str(self.scheduler_file), timeout='120s') as client:
            client.wait_for_workers(workers, timeout=TIMEOUT_S)
        return self._address()

    def _address(self):
        try:
            return json.loads(self.scheduler_file.read_text())['address']
        except (OSError, ValueError, KeyError):
            return None

    def worker_of(self, pid):
        """The name of the worker whose process group holds process `pid`."""
        group = os.getpgid(pid)
        return next(name for name, p in self.procs.items() if p.pid == group and name.startswith('worker'))

    def signal(self, name, sig):
        with contextlib.suppress(ProcessLookupError):
            os.killpg(self.procs[name].pid, sig)

    def stop(self):
        """Workers first, then the scheduler: SIGTERM, and SIGKILL to what is left after 30 s."""
        for names in ([n for n in self.procs if n != 'scheduler'], ['scheduler']):
            for name in names:
                self.signal(name, signal.SIGCONT)
                self.signal(name, signal.SIGTERM)
            for name in names:
                try:
                    self.procs[name].wait(timeout=30)
                except subprocess.TimeoutExpired:
                    pass
                self.signal(name, signal.SIGKILL)  # the group: also a worker process its nanny left behind
                self.procs[name].wait()


@pytest.fixture
def dask_processes(tmp_path):
    cluster = DaskProcesses(tmp_path)
    try:
        yield cluster
    finally:
        cluster.stop()


def run_files(out):
    return {p.name: p.read_bytes() for p in sorted((out / 'runs').iterdir())
            if p.name.startswith('run_') and p.suffix == '.npy'}


def records(out):
    return {int(p.stem[4:]): json.loads(p.read_text()) for p in (out / 'runs').glob('run_*.json')}


def test_a_scheduler_and_two_worker_processes_lose_nothing_when_one_is_killed(dask_processes, tmp_path):
    address = dask_processes.start(workers=2)
    assert address.startswith('tcp://127.0.0.1:')
    out = tmp_path / 'dask'
    runs = out / 'runs'
    host = socket.gethostname()
    killed = {}

    def kill_a_worker_inside_a_run(campaign):
        """After the first record: stop the worker that wrote it (SIGSTOP to its group), and if it is
        inside a run (its work directory .run_<i>.<host>.<pid>.tmp exists) kill it with its nanny;
        otherwise let it go on and look again. Stopped, it cannot finish the run in between."""
        wait_for('the first run recorded', lambda: any(runs.glob('run_*.json')), processes=[campaign])
        first = json.loads(next(runs.glob('run_*.json')).read_text())
        pid, name = first['pid'], dask_processes.worker_of(first['pid'])
        inside = re.compile(rf'\.run_(\d{{7}})\.{re.escape(host)}\.{pid}\.tmp')
        deadline = time.monotonic() + TIMEOUT_S
        while campaign.poll() is None and time.monotonic() < deadline:
            dask_processes.signal(name, signal.SIGSTOP)
            held = [int(m.group(1)) for m in map(inside.fullmatch, os.listdir(runs)) if m]
            if held:
                # The records written so far, as they are while the worker is stopped
                killed.update(worker=name, pid=pid, run=held[0], before=records(out))
                dask_processes.signal(name, signal.SIGKILL)
                return
            dask_processes.signal(name, signal.SIGCONT)
            time.sleep(0.005)

    campaign = subprocess.Popen(campaign_command() + [str(CAMPAIGN), '--out', str(out), '--index-range', f'0:{RUNS}',
                                                      '--scheduler', address],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    killer = threading.Thread(target=kill_a_worker_inside_a_run, args=(campaign,))
    killer.start()
    try:
        _, log = campaign.communicate(timeout=TIMEOUT_S)
    finally:
        if campaign.poll() is None:
            campaign.kill()
            campaign.wait()
        killer.join()
    assert campaign.returncode == 0, log
    assert killed, f'no worker was killed inside a run before the campaign ended:\n{log}'
    print(f"killed {killed['worker']} (PID {killed['pid']}) inside run {killed['run']}, "
          f"{len(killed['before'])} of {RUNS} runs recorded then")
    assert dask_processes.procs[killed['worker']].wait(timeout=60) == -signal.SIGKILL
    # The one invocation finished every run once, none failed or was found finished before.
    assert f'{RUNS} finished, 0 failed, 0 skipped' in log, log

    recs = records(out)
    assert sorted(recs) == list(range(RUNS)) and {r['status'] for r in recs.values()} == {'ok'}
    # The run the killed worker was inside was done again, by the other worker.
    assert recs[killed['run']]['pid'] != killed['pid']
    # A run finished before the kill was not run again, also one whose result the driver had not
    # fetched from the killed worker yet (Dask computes such a task again: the run is found finished).
    assert {i: recs[i] for i in killed['before']} == killed['before']
    assert any(r['pid'] == killed['pid'] for r in killed['before'].values())
    # Nothing of the killed attempt is left: one data file and one record per run, no temporary files.
    assert sorted(os.listdir(runs)) == sorted([f'run_{i:07d}.npy' for i in range(RUNS)]
                                              + [f'run_{i:07d}.json' for i in range(RUNS)])

    # The same runs in one process, no Dask: the same bytes, and the same manifest.
    serial = tmp_path / 'serial'
    subprocess.run(campaign_command() + [str(CAMPAIGN), '--out', str(serial), '--index-range', f'0:{RUNS}',
                                         '--serial', '--quiet'], check=True, timeout=TIMEOUT_S)
    files = run_files(out)
    assert len(files) == RUNS and files == run_files(serial)
    manifest = (out / 'manifest.csv').read_bytes()
    assert manifest == (serial / 'manifest.csv').read_bytes()
    rows = list(csv.DictReader(manifest.decode().splitlines()))
    assert [int(r['index']) for r in rows] == list(range(RUNS))
    assert {r['status'] for r in rows} == {'ok'} and all((out / r['file']).is_file() for r in rows)
    # --manifest-only (after a job array) rebuilds the same table from the records.
    subprocess.run(campaign_command() + [str(CAMPAIGN), '--out', str(out), '--manifest-only', '--quiet'],
                   check=True, timeout=TIMEOUT_S)
    assert (out / 'manifest.csv').read_bytes() == manifest
