#!/usr/bin/env python3
"""Measures bearing_sim_node from a running launch (e.g. roslaunch bearing_sim ct_gantry.launch):
CPU use of the node, chunk publish jitter and the lag of simulated behind wall time.

  scripts/measure_node.py [--ns /bearing] [--node bearing_sim_node] [--duration 60]

Figures:
  - CPU: utime + stime of the node process (from /proc) over the run, % of one core.
  - Chunk lag at arrival: arrival wall time minus the simulated time of the chunk's last
    sample (header.stamp + (n-1)/rate); p50/p99/max. Includes ROS transport and this
    script's own scheduling; an upper bound of the node's publish lag.
  - Inter-arrival jitter: |arrival interval - chunk period|, p50/p99.
  - The node's own account from /diagnostics (lag at publication p50/p99/max, overruns).
  - Lag after the run: median chunk lag over the last second.
  - Sample contiguity: gaps and repeats of first_sample.
"""
import argparse
import os
import sys
import threading
import time

import rospy
import rosgraph
from diagnostic_msgs.msg import DiagnosticArray

from bearing_sim.msg import VibrationChunk


def node_pid(node_name):
    master = rosgraph.Master('/measure_node')
    uri = master.lookupNode(node_name)
    import xmlrpc.client
    code, _, pid = xmlrpc.client.ServerProxy(uri).getPid('/measure_node')
    return pid if code == 1 else None


def cpu_seconds(pid):
    with open('/proc/%d/stat' % pid) as f:
        fields = f.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


def percentile(values, p):
    if not values:
        return float('nan')
    v = sorted(values)
    return v[min(len(v) - 1, max(0, int(round(p * len(v) + 0.5)) - 1))]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--ns', default='/bearing')
    parser.add_argument('--node', default='bearing_sim_node')
    parser.add_argument('--duration', type=float, default=60.0, help='wall seconds to measure')
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node('measure_node', anonymous=True, disable_signals=True)
    node_name = args.ns.rstrip('/') + '/' + args.node
    pid = node_pid(node_name)
    if pid is None:
        sys.exit('cannot find the pid of %s' % node_name)
    try:  # nodelets (ct_gantry.launch's default): the simulation runs in the manager's process
        manager_pid = node_pid(args.ns.rstrip('/') + '/bearing_nodelet_manager')
    except Exception:
        manager_pid = None
    label = node_name
    if manager_pid:
        pid = manager_pid
        label += ' (nodelet in bearing_nodelet_manager: CPU of the manager, display and LCM bridge included)'

    lock = threading.Lock()
    arrivals = []  # (wall arrival, sim time of last sample, first_sample, n, rate)
    diag = {}

    def on_chunk(msg):
        now = time.time()
        n = len(msg.accel_x)
        with lock:
            arrivals.append((now, msg.header.stamp.to_sec() + (n - 1) / msg.sample_rate, msg.first_sample, n,
                             msg.sample_rate))

    def on_diag(msg):
        for s in msg.status:
            if s.name.startswith(node_name.lstrip('/')) and s.name.endswith('Real time'):
                with lock:
                    diag.clear()
                    diag.update({kv.key: kv.value for kv in s.values})

    rospy.Subscriber(args.ns.rstrip('/') + '/vibration', VibrationChunk, on_chunk, queue_size=1000, tcp_nodelay=True)
    rospy.Subscriber('/diagnostics', DiagnosticArray, on_diag, queue_size=10)
    time.sleep(1.0)  # connect
    cpu0, t0 = cpu_seconds(pid), time.time()
    with lock:
        start = len(arrivals)
    time.sleep(args.duration)
    cpu1, t1 = cpu_seconds(pid), time.time()
    with lock:
        run = arrivals[start:]
    time.sleep(1.2)  # one more diagnostics message
    with lock:
        d = dict(diag)
    if len(run) < 10:
        sys.exit('too few chunks received (%d)' % len(run))

    gaps = repeats = 0
    for a, b in zip(run, run[1:]):
        expected = a[2] + a[3]
        gaps += b[2] > expected
        repeats += b[2] < expected
    lags = [w - s for (w, s, _, _, _) in run]
    intervals = [abs((b[0] - a[0]) - a[3] / a[4]) for a, b in zip(run, run[1:])]
    last_second = [w - s for (w, s, _, _, _) in run if w >= run[-1][0] - 1.0]
    samples = run[-1][2] + run[-1][3] - run[0][2]
    print('node %s (pid %d), %.1f s measured, %d chunks, %d samples (%.1f per wall second)' % (
        label, pid, t1 - t0, len(run), samples, samples / (run[-1][0] - run[0][0] + run[0][3] / run[0][4])))
    print('CPU: %.1f %% of one core' % (100.0 * (cpu1 - cpu0) / (t1 - t0)))
    print('chunk lag at arrival (ms): p50 %.3f  p99 %.3f  max %.3f' % (
        1e3 * percentile(lags, 0.5), 1e3 * percentile(lags, 0.99), 1e3 * max(lags)))
    print('inter-arrival jitter |dt - period| (ms): p50 %.3f  p99 %.3f' % (
        1e3 * percentile(intervals, 0.5), 1e3 * percentile(intervals, 0.99)))
    print('lag after the run (median of the last second, ms): %.3f' % (1e3 * percentile(last_second, 0.5)))
    print('gaps %d, repeats %d' % (gaps, repeats))
    if d:
        print('node diagnostics: lag p50 %s ms, p99 %s ms, max %s ms, overruns %s, samples published %s' % (
            d.get('lag p50 (ms)'), d.get('lag p99 (ms)'), d.get('lag max (ms)'), d.get('overruns'),
            d.get('samples published')))
    rospy.signal_shutdown('done')


if __name__ == '__main__':
    main()
