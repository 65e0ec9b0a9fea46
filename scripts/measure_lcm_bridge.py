#!/usr/bin/env python3
"""Measures lcm_bridge from a running launch (ct_gantry.launch + lcm_bridge.launch):
CPU use of the bridge and what it forwarded, from its /diagnostics counters.

  scripts/measure_lcm_bridge.py [--ns /bearing] [--node lcm_bridge] [--duration 30]

Figures, over the run: CPU (utime + stime from /proc, % of one core), messages and MB
published on LCM per second, chunks per second per chunk route, and the publish failures,
drops (queue full) and rejections that occurred.
"""
import argparse
import os
import sys
import threading
import time
import xmlrpc.client

import rosgraph
import rospy
from diagnostic_msgs.msg import DiagnosticArray


def node_pid(node_name):
    uri = rosgraph.Master('/measure_lcm_bridge').lookupNode(node_name)
    code, _, pid = xmlrpc.client.ServerProxy(uri).getPid('/measure_lcm_bridge')
    return pid if code == 1 else None


def cpu_seconds(pid):
    with open('/proc/%d/stat' % pid) as f:
        fields = f.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


class LatestStatus:
    def __init__(self, name):
        self.name, self.values, self.event = name, None, threading.Event()

    def __call__(self, msg):
        for s in msg.status:
            if s.name == self.name:
                self.values = {kv.key: kv.value for kv in s.values}
                self.event.set()

    def next(self, timeout):
        self.event.clear()
        if not self.event.wait(timeout):
            sys.exit('no /diagnostics status "%s" within %.0f s' % (self.name, timeout))
        return dict(self.values)


def forwarded(values):
    """Route label -> forwarded count, from '<n> forwarded, <m> rejected'."""
    return {k: int(v.split()[0]) for k, v in values.items() if ' -> ' in k}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--ns', default='/bearing')
    parser.add_argument('--node', default='lcm_bridge')
    parser.add_argument('--duration', type=float, default=30.0, help='wall seconds to measure')
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node('measure_lcm_bridge', anonymous=True, disable_signals=True)
    node_name = args.ns.rstrip('/') + '/' + args.node
    pid = node_pid(node_name)
    if pid is None:
        sys.exit('node %s not found' % node_name)
    status = LatestStatus(node_name.lstrip('/') + ': LCM')
    rospy.Subscriber('/diagnostics', DiagnosticArray, status, queue_size=100)

    v0, c0, t0 = status.next(10.0), cpu_seconds(pid), time.monotonic()
    time.sleep(args.duration)
    v1, c1, t1 = status.next(10.0), cpu_seconds(pid), time.monotonic()
    # Counters are sampled at the bridge's 1 s diagnostic period: rates over the counters' span.
    dt = t1 - t0
    print('lcm_bridge %s on %s, %.1f s' % (node_name, v1['LCM URL'], dt))
    print('CPU: %.2f %% of one core' % (100.0 * (c1 - c0) / dt))
    print('published: %.1f messages/s, %.3f MB/s' % ((int(v1['published']) - int(v0['published'])) / dt,
                                                    (float(v1['MB published']) - float(v0['MB published'])) / dt))
    f0, f1 = forwarded(v0), forwarded(v1)
    for route in sorted(f1):
        print('  %s: %.1f /s' % (route, (f1[route] - f0.get(route, 0)) / dt))
    for key in ('publish failures', 'dropped (queue full)', 'rejected (not convertible)'):
        print('%s: %d' % (key, int(v1[key]) - int(v0[key])))
    print('largest queue so far: %s MB' % v1['largest queue (MB)'])


if __name__ == '__main__':
    main()
