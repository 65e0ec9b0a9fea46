#!/usr/bin/env python3
"""Soak run of the main job: starts `roslaunch bearing_sim ct_gantry.launch record:=true`
(display on, every topic recorded) for a given wall time, listens to the vibration stream
the whole time, and reports whether the node kept its real-time contract.

  scripts/soak_node.py --duration 3600 [--bag-dir DIR] [--keep-bag] [--json FILE] [-- launch args...]

Run it from a shell with the package's environment (source scripts/env.sh and
build/devel/setup.bash, or the install space's setup.bash). Figures:
  - samples published vs expected: the running sample index received over the run against
    wall time x rate (the node's lead and one chunk are the only expected difference);
  - gaps and repeats of first_sample (every sample once, in order);
  - overruns (chunks published more than one chunk period after their time) and the node's
    lag p50/p99/max at publication, from its /diagnostics;
  - lag at arrival here: arrival wall time minus the time of a chunk's last sample,
    p50/p99/max over the whole run (includes ROS transport and this script's scheduling);
  - CPU of every process of the launch (roslaunch and all it started: master, rosout, nodes,
    the nodelet manager and its loaders) and of the whole launch, % of one core over the run,
    after a warm-up;
  - resident memory (RSS) of the simulation's process (the nodelet manager when the launch
    runs nodelets) at the start and at the end, and its largest value: a leak shows as growth.
The machine's CPU and load average are printed with the figures. Ctrl-C (SIGINT) or SIGTERM
ends the soak early with the figures of the time measured so far. Exit status 0 when the run
completed (whatever the figures); 1 when the launch failed or nothing was received.
"""
import argparse
import json
import os
import platform
import signal
import subprocess
import sys
import tempfile
import threading
import time

import rospy
from diagnostic_msgs.msg import DiagnosticArray

from bearing_sim.msg import VibrationChunk
from measure_node import cpu_seconds, node_pid, percentile

LAUNCH_NODES = ['/bearing/bearing_sim_node', '/bearing/bearing_viz', '/bearing/recorder']
MANAGER = '/bearing/bearing_nodelet_manager'


def launch_processes(root_pid):
    """pid -> name of root_pid and every process below it (roslaunch starts each node in a
    session of its own: the parent links, not the session, hold the launch together)."""
    children, names = {}, {}
    for d in os.listdir('/proc'):
        if not d.isdigit():
            continue
        try:
            with open('/proc/%s/stat' % d) as f:
                stat = f.read()
            with open('/proc/%s/cmdline' % d, 'rb') as f:
                argv = f.read().decode(errors='replace').split('\0')
        except OSError:
            continue
        pid = int(d)
        ppid = int(stat.rsplit(')', 1)[1].split()[1])
        children.setdefault(ppid, []).append(pid)
        ros_name = [a[len('__name:='):] for a in argv if a.startswith('__name:=')]
        names[pid] = ros_name[0] if ros_name else stat[stat.index('(') + 1:stat.rindex(')')]
    found, todo = {}, [root_pid]
    while todo:
        pid = todo.pop()
        if pid in names:
            found[pid] = names[pid]
        todo.extend(children.get(pid, []))
    return found


def rss_mib(pid):
    with open('/proc/%d/status' % pid) as f:
        for line in f:
            if line.startswith('VmRSS:'):
                return int(line.split()[1]) / 1024.0
    return float('nan')


def cpu_model():
    try:
        with open('/proc/cpuinfo') as f:
            for line in f:
                if line.startswith('model name'):
                    return line.split(':', 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or 'unknown'


def wait_for_pid(name, timeout_s):
    end = time.time() + timeout_s
    while time.time() < end:
        try:
            pid = node_pid(name)
            if pid:
                return pid
        except Exception:  # master or node not up yet
            pass
        time.sleep(0.5)
    return None


class Listener:
    """Every vibration chunk's first_sample, size and arrival; the node's Real time status."""

    def __init__(self, ns, node_name):
        self.lock = threading.Lock()
        self.node_name = node_name.lstrip('/')
        self.recording = False
        self.first_index = None
        self.next_index = None
        self.first_arrival = self.last_arrival = None
        self.gaps = self.repeats = self.chunks = 0
        self.lags = []
        self.diag = {}
        rospy.Subscriber(ns + '/vibration', VibrationChunk, self.on_chunk, queue_size=10000, tcp_nodelay=True)
        rospy.Subscriber('/diagnostics', DiagnosticArray, self.on_diag, queue_size=10)

    def on_chunk(self, msg):
        now = time.time()
        n = len(msg.accel_x)
        with self.lock:
            if not self.recording:
                return
            if self.next_index is None:
                self.first_index, self.first_arrival, self.first_size = msg.first_sample, now, n
            else:
                self.gaps += msg.first_sample > self.next_index
                self.repeats += msg.first_sample < self.next_index
            self.next_index = msg.first_sample + n
            self.last_arrival = now
            self.chunks += 1
            self.lags.append(now - (msg.header.stamp.to_sec() + (n - 1) / msg.sample_rate))
            self.rate = msg.sample_rate

    def on_diag(self, msg):
        for s in msg.status:
            if s.name.startswith(self.node_name) and s.name.endswith('Real time'):
                with self.lock:
                    self.diag = {kv.key: kv.value for kv in s.values}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--duration', type=float, default=3600.0, help='wall seconds to measure (after warm-up)')
    parser.add_argument('--warmup', type=float, default=20.0, help='wall seconds before measuring')
    parser.add_argument('--bag-dir', default=None, help='where the bag goes (default: a temporary directory)')
    parser.add_argument('--keep-bag', action='store_true', help='keep the bag (default: deleted after the run)')
    parser.add_argument('--json', default=None, help='also write the figures to this file')
    parser.add_argument('launch_args', nargs='*', help='extra ct_gantry.launch arguments, e.g. lcm:=true')
    args = parser.parse_args()
    if not (args.duration > 0 and args.warmup >= 0):
        sys.exit('--duration must be > 0 and --warmup >= 0')

    bag_dir = args.bag_dir or tempfile.mkdtemp(prefix='bearing_sim_soak_')
    launch = subprocess.Popen(
        ['roslaunch', 'bearing_sim', 'ct_gantry.launch', 'record:=true', 'viz:=true', 'output:=log',
         'bag_dir:=' + bag_dir, 'bag_name:=soak'] + args.launch_args,
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, start_new_session=True)
    report = {}
    try:
        pids = {}
        node = LAUNCH_NODES[0]
        pids[node] = wait_for_pid(node, 60.0)
        if pids[node] is None:
            sys.exit('the launch did not start %s' % node)
        rospy.init_node('soak_node', anonymous=True, disable_signals=True)
        listener = Listener('/bearing', node)
        for name in LAUNCH_NODES[1:]:
            pids[name] = wait_for_pid(name, 30.0)
        try:  # nodelets: the simulation runs in the manager, its node name is the loader's
            sim_pid = node_pid(MANAGER) or pids[node]
        except Exception:
            sim_pid = pids[node]
        time.sleep(args.warmup)

        procs = launch_processes(launch.pid)
        cpu0 = {p: cpu_seconds(p) for p in procs}
        rss_start = rss_mib(sim_pid)
        rss_max = rss_start
        with listener.lock:
            listener.recording = True
            overruns_before = int(listener.diag.get('overruns', 0))  # start-up is not the soak's
        # Ctrl-C or SIGTERM ends the soak early with the figures of the time measured so far.
        stop = threading.Event()
        for number in (signal.SIGINT, signal.SIGTERM):
            signal.signal(number, lambda *_: stop.set())
        t0 = time.time()
        next_print = t0 + 60.0
        while time.time() - t0 < args.duration and not stop.is_set():
            if launch.poll() is not None:
                sys.exit('the launch ended early (exit %s): %s' % (launch.returncode, launch.stderr.read().decode()[-2000:]))
            time.sleep(1.0)
            rss_max = max(rss_max, rss_mib(sim_pid))
            if time.time() >= next_print:
                next_print += 60.0
                with listener.lock:
                    print('%6.0f s: %d chunks, gaps %d, repeats %d, overruns %s, RSS %.1f MiB' % (
                        time.time() - t0, listener.chunks, listener.gaps, listener.repeats,
                        int(listener.diag.get('overruns', 0)) - overruns_before, rss_mib(sim_pid)), flush=True)
        t1 = time.time()
        with listener.lock:
            listener.recording = False
        cpu1 = {}
        for p in cpu0:
            try:
                cpu1[p] = cpu_seconds(p)
            except OSError:  # ended during the run
                pass
        rss_end = rss_mib(sim_pid)
        time.sleep(2.5)  # the node's next diagnostics, with the whole run counted
        with listener.lock:
            if not listener.chunks:
                sys.exit('no vibration chunks received')
            received = listener.next_index - listener.first_index
            span_s = listener.last_arrival - listener.first_arrival
            # The first chunk arrived whole, then the stream at the node's rate.
            expected = span_s * listener.rate + listener.first_size
            lags = sorted(listener.lags)
            report = {
                'cpu_model': cpu_model(),
                'load_average_end': os.getloadavg(),
                'duration_s': t1 - t0,
                'chunks': listener.chunks,
                'samples_received': received,
                'samples_expected_from_wall_time': expected,
                'gaps': listener.gaps,
                'repeats': listener.repeats,
                'overruns': int(listener.diag.get('overruns', 0)) - overruns_before,
                'overruns_since_node_start': listener.diag.get('overruns'),
                'node_lag_ms': {k: listener.diag.get('lag %s (ms)' % k) for k in ('p50', 'p99', 'max')},
                'node_memory_locked': listener.diag.get('memory locked'),
                'node_scheduling': '%s (simulation), %s (publisher)' % (
                    listener.diag.get('simulation thread scheduling'), listener.diag.get('publisher thread scheduling')),
                'node_lead_ms': listener.diag.get('lead (ms)'),
                'simd_target': listener.diag.get('SIMD target'),
                'arrival_lag_ms': {'p50': 1e3 * percentile(lags, 0.5), 'p99': 1e3 * percentile(lags, 0.99),
                                   'max': 1e3 * lags[-1]},
                'cpu_percent_of_one_core': {'%s (pid %d)' % (procs[p], p): 100.0 * (cpu1[p] - cpu0[p]) / (t1 - t0)
                                            for p in sorted(cpu1)},
                'cpu_percent_whole_launch': 100.0 * sum(cpu1[p] - cpu0[p] for p in cpu1) / (t1 - t0),
                'nodelets': sim_pid != pids[node],
                'node_rss_mib': {'start': rss_start, 'end': rss_end, 'max': rss_max},
            }
    finally:
        os.killpg(launch.pid, signal.SIGINT)
        try:
            launch.wait(timeout=60)
        except subprocess.TimeoutExpired:
            os.killpg(launch.pid, signal.SIGKILL)
        if not args.keep_bag and not args.bag_dir:
            subprocess.call(['rm', '-rf', bag_dir])

    r = report
    print('soak of ct_gantry.launch (display on, record:=true) on %s (SIMD target %s), load average at the end '
          '%.2f %.2f %.2f' % ((r['cpu_model'], r['simd_target']) + tuple(r['load_average_end'])))
    print('  %.0f s measured, %d chunks' % (r['duration_s'], r['chunks']))
    print('  samples received %d, expected from wall time %.0f (difference %.0f)' % (
        r['samples_received'], r['samples_expected_from_wall_time'],
        r['samples_received'] - r['samples_expected_from_wall_time']))
    print('  gaps %d, repeats %d, overruns %d (since the node started, warm-up included: %s)' % (
        r['gaps'], r['repeats'], r['overruns'], r['overruns_since_node_start']))
    print('  node lag at publication (ms, its last minute): p50 %s, p99 %s, max %s; lead %s ms' % (
        r['node_lag_ms']['p50'], r['node_lag_ms']['p99'], r['node_lag_ms']['max'], r['node_lead_ms']))
    print('  scheduling: %s; memory locked: %s' % (r['node_scheduling'], r['node_memory_locked']))
    print('  lag at arrival here (ms): p50 %.2f, p99 %.2f, max %.2f' % (
        r['arrival_lag_ms']['p50'], r['arrival_lag_ms']['p99'], r['arrival_lag_ms']['max']))
    for n, c in r['cpu_percent_of_one_core'].items():
        print('  CPU %s: %.1f %% of one core' % (n, c))
    print('  CPU of the whole launch (%s): %.1f %% of one core' % (
        'nodelets in one manager' if r['nodelets'] else 'standalone nodes', r['cpu_percent_whole_launch']))
    print('  RSS of the simulation\'s process (MiB): start %.1f, end %.1f, max %.1f' % (
        r['node_rss_mib']['start'], r['node_rss_mib']['end'], r['node_rss_mib']['max']))
    if args.json:
        with open(args.json, 'w') as f:
            json.dump(r, f, indent=2)
    rospy.signal_shutdown('done')


if __name__ == '__main__':
    main()
