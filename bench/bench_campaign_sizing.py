#!/usr/bin/env python3
"""Sizing a real campaign (issue 34; docs/datasets.md, "Sizing a campaign"): the first runs of the
shipped campaigns as they are (config/campaigns/deep_groove_defects.yaml, cwru_rig.yaml), made
serially in this process and on a Dask cluster of separate processes (`dask scheduler` and
2 x `dask worker --nthreads 1` on localhost, as on a cluster's nodes). Prints per campaign:
the CPU per run of the serial process (simulation, encoding, writing: what a core spends on a
run), runs per core-hour and core-hours for 1,000,000 runs from it, the simulation's own CPU per
run, bytes per run; on Dask the wall time and runs per core-hour of the 2 cores' wall time; and
how loaded the machine was (load average, the CPU other processes took meanwhile).
Usage: source build/devel/setup.bash; /usr/bin/python3 bench/bench_campaign_sizing.py [runs, default 200] [CAMPAIGN.yaml ...]"""
import contextlib
import json
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import bearing_sim
from bearing_sim.campaign import Campaign, run_campaign
from bearing_sim.campaign.store import RunStore

ROOT = pathlib.Path(__file__).resolve().parents[1]
WORKERS = 2


def machine_cpu_s():
    """CPU seconds all processes of the machine have used (busy jiffies of /proc/stat)."""
    fields = [int(x) for x in open('/proc/stat').readline().split()[1:]]
    return (sum(fields) - fields[3] - fields[4]) / os.sysconf('SC_CLK_TCK')


def own_cpu_s():
    t = os.times()
    return t.user + t.system


@contextlib.contextmanager
def dask_processes(directory):
    """A scheduler and WORKERS single-threaded workers, each a process group of its own."""
    procs = []
    directory.mkdir(parents=True)
    scheduler_file = directory / 'scheduler.json'

    def start(args):
        procs.append(subprocess.Popen(['/usr/bin/dask'] + args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                      cwd=directory, start_new_session=True))
    try:
        start(['scheduler', '--host', '127.0.0.1', '--port', '0', '--no-dashboard', '--no-show',
               '--scheduler-file', str(scheduler_file)])
        for k in range(WORKERS):
            start(['worker', '--scheduler-file', str(scheduler_file), '--host', '127.0.0.1', '--nthreads', '1',
                   '--no-dashboard', '--local-directory', str(directory / f'worker{k}'), '--death-timeout', '120'])
        from dask.distributed import Client
        deadline = time.monotonic() + 300
        while not scheduler_file.exists() and time.monotonic() < deadline:
            time.sleep(0.1)
        with Client(scheduler_file=str(scheduler_file), timeout='300s') as client:
            client.wait_for_workers(WORKERS, timeout=300)
        yield json.loads(scheduler_file.read_text())['address']
    finally:
        for p in reversed(procs):
            with contextlib.suppress(ProcessLookupError):
                os.killpg(p.pid, signal.SIGTERM)
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:
                with contextlib.suppress(ProcessLookupError):
                    os.killpg(p.pid, signal.SIGKILL)
                p.wait()


def measure(campaign, out, runs, **where):
    machine0, own0, start = machine_cpu_s(), own_cpu_s(), time.perf_counter()
    s = run_campaign(campaign, out, indices=range(runs), log=lambda line: None, **where)
    wall, own, machine = time.perf_counter() - start, own_cpu_s() - own0, machine_cpu_s() - machine0
    records = [r for r in RunStore(out, campaign).records() if r['status'] == 'ok']
    assert s['failed'] == 0 and len(records) == runs, s
    return {'wall': wall, 'own_cpu': own, 'machine_cpu': machine, 'load': os.getloadavg()[0],
            'sim_cpu': sum(r['cpu_s'] for r in records) / runs, 'bytes': sum(r['bytes'] for r in records) / runs,
            'simulated': sum(r['simulated_s'] for r in records) / runs}


def main():
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 200
    paths = [pathlib.Path(p) for p in sys.argv[2:]] or [ROOT / 'config' / 'campaigns' / 'deep_groove_defects.yaml',
                                                        ROOT / 'config' / 'campaigns' / 'cwru_rig.yaml']
    cores = len(os.sched_getaffinity(0))
    print(f'{bearing_sim.cpu_model_name()}, SIMD {bearing_sim.simd_target_name()}, {cores} cores; '
          f'load average before {os.getloadavg()[0]:.2f}', flush=True)
    work = pathlib.Path(tempfile.mkdtemp(prefix='bench_campaign_sizing_'))
    try:
        for path in paths:
            c = Campaign.load(path)
            serial = measure(c, work / f'{c.name}_serial', runs, serial=True)
            per_run = serial['own_cpu'] / runs
            others = max(serial['machine_cpu'] - serial['own_cpu'], 0.0) / serial['wall']
            print(f'{c.name}: {runs} runs of {serial["simulated"]:g} s simulated, serial: {per_run:.4f} CPU s per run '
                  f'(simulation {serial["sim_cpu"]:.4f} s), {3600 / per_run:,.0f} runs per core-hour, '
                  f'{per_run * 1e6 / 3600:,.1f} core-hours per 1,000,000 runs; wall {serial["wall"]:.1f} s; '
                  f'{serial["bytes"] / 1e3:.0f} kB per run; other processes {others:.2f} of {cores} cores, '
                  f'load average {serial["load"]:.2f}', flush=True)
            with dask_processes(work / f'{c.name}_cluster') as address:
                d = measure(c, work / f'{c.name}_dask', runs, scheduler=address)
            others = max(d['machine_cpu'] - 0.0, 0.0) / d['wall']  # machine-wide, the workers included
            print(f'{c.name}: on dask scheduler + {WORKERS} workers: wall {d["wall"]:.1f} s, {runs / d["wall"]:.2f} runs/s, '
                  f'{runs / (d["wall"] * WORKERS) * 3600:,.0f} runs per core-hour of the {WORKERS} workers\' wall time '
                  f'(machine busy {others:.2f} of {cores} cores meanwhile, load average {d["load"]:.2f})', flush=True)
            a = sorted((work / f'{c.name}_serial' / 'runs').glob('run_*.npy'))
            assert [p.read_bytes() for p in a] == [(work / f'{c.name}_dask' / 'runs' / p.name).read_bytes() for p in a]
    finally:
        shutil.rmtree(work)


if __name__ == '__main__':
    main()
