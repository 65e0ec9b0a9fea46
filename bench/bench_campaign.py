#!/usr/bin/env python3
"""Throughput of dataset campaigns (docs/datasets.md, "Speed and cost"): runs of
config/campaigns/deep_groove_defects.yaml lengthened to 10 s, on a Dask LocalCluster of 1
and then 2 single-threaded workers, and serially. Prints runs per second, simulated seconds
per second per core (CPU of the runs), bytes per run, the extrapolation to a
1,000,000-run campaign, and how loaded the machine was (load average, and the CPU the other
processes took during each measurement).
Usage: source build/devel/setup.bash; /usr/bin/python3 bench/bench_campaign.py [runs per case, default 8]"""
import logging
import os
import pathlib
import shutil
import sys
import tempfile
import time

import yaml
from dask.distributed import Client, LocalCluster

import bearing_sim
from bearing_sim.campaign import Campaign, run_campaign
from bearing_sim.campaign.store import RunStore

ROOT = pathlib.Path(__file__).resolve().parents[1]
DURATION_S = 10.0


def cpu_jiffies():
    """(busy, total) jiffies of the whole machine, from /proc/stat."""
    fields = [int(x) for x in open('/proc/stat').readline().split()[1:]]
    idle = fields[3] + fields[4]
    return sum(fields) - idle, sum(fields)


def own_cpu_s(pids):
    total = 0.0
    for pid in pids:
        try:
            f = open(f'/proc/{pid}/stat').read().rsplit(')', 1)[1].split()
            total += (int(f[11]) + int(f[12])) / os.sysconf('SC_CLK_TCK')
        except OSError:
            pass
    return total


def measure(label, campaign, out, client=None, serial=False, pids=()):
    busy0, total0 = cpu_jiffies()
    mine0 = own_cpu_s(pids)
    start = time.perf_counter()
    s = run_campaign(campaign, out, client=client, serial=serial, log=lambda line: None)
    wall = time.perf_counter() - start
    busy1, total1 = cpu_jiffies()
    mine = own_cpu_s(pids) - mine0
    hz = os.sysconf('SC_CLK_TCK')
    machine_busy_s = (busy1 - busy0) / hz
    others_s = max(machine_busy_s - mine, 0.0)
    cores = os.cpu_count()
    ok = [r for r in RunStore(out, campaign).records() if r['status'] == 'ok']
    cpu = sum(r['cpu_s'] for r in ok)
    simulated = sum(r['simulated_s'] for r in ok)
    size = sum(r['bytes'] for r in ok) / max(len(ok), 1)
    print(f'{label:28s} runs {len(ok):3d} failed {s["failed"]}  wall {wall:6.1f} s  '
          f'{len(ok) / wall:6.3f} runs/s  {simulated / wall:6.1f} simulated s/s  '
          f'{simulated / cpu:6.1f} simulated s per CPU s of a run  '
          f'CPU per run {cpu / len(ok):.3f} s  {size / 1e6:.2f} MB/run  '
          f'other processes: {others_s / wall:.2f} of {cores} cores  load avg {os.getloadavg()[0]:.2f}')
    return {'wall': wall, 'runs': len(ok), 'cpu': cpu, 'simulated': simulated, 'bytes': size, 'process_cpu': mine}


def main():
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 8
    doc = yaml.safe_load((ROOT / 'config' / 'campaigns' / 'deep_groove_defects.yaml').read_text())
    doc['scenario']['duration_s'] = DURATION_S
    doc['count'] = runs
    work = pathlib.Path(tempfile.mkdtemp(prefix='bench_campaign_'))
    # Laid out as config/: the campaign finds the shipped bearing and sensor in ../bearings, ../sensors.
    (work / 'campaigns').mkdir()
    for folder in ('bearings', 'sensors'):
        (work / folder).symlink_to(ROOT / 'config' / folder)
    path = work / 'campaigns' / 'bench_campaign.yaml'
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    try:
        c = Campaign.load(path)
        print(f'{bearing_sim.cpu_model_name()}, SIMD {bearing_sim.simd_target_name()}, {os.cpu_count()} cores, '
              f'load average before {os.getloadavg()}')
        results = {}
        results['serial'] = measure('serial (1 core)', c, work / 'serial', serial=True, pids=[os.getpid()])
        for n in (1, 2):
            t0 = time.perf_counter()
            cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
                                   silence_logs=logging.ERROR)
            client = Client(cluster)
            started = time.perf_counter() - t0
            pids = list(client.run(os.getpid).values()) + [os.getpid()]
            pids += [p.pid for p in __import__('psutil').Process().children(recursive=True)]
            results[n] = measure(f'LocalCluster {n} worker(s)', c, work / f'dask{n}', client=client,
                                 pids=set(pids))
            print(f'  (cluster start {started:.1f} s, not in the figures)')
            client.close()
            cluster.close()
        one, two = results[1], results[2]
        print(f'speed-up 1 -> 2 workers: {two["runs"] / two["wall"] / (one["runs"] / one["wall"]):.2f}x')
        # Core time of a run: the serial process's CPU per run (simulation, encoding, writing).
        per_run_cpu = results['serial']['process_cpu'] / results['serial']['runs']
        size = results['serial']['bytes']
        print(f'1,000,000 runs of {DURATION_S:g} s: {per_run_cpu * 1e6 / 3600:.0f} core-hours '
              f'({per_run_cpu:.3f} CPU s per run, of which the simulation {results["serial"]["cpu"] / results["serial"]["runs"]:.3f} s), '
              f'{size * 1e6 / 1e12:.2f} TB of NPY ({size / 1e6:.2f} MB per run)')
    finally:
        shutil.rmtree(work)


if __name__ == '__main__':
    main()
