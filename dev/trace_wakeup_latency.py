#!/usr/bin/python3
"""What delays the node's real-time threads: a kernel trace of their wake-ups.

Records, for DURATION seconds, every wake-up of the SCHED_FIFO threads of process PID (the
node, or the nodelet manager that runs the simulation) and when each one got the CPU, with the
kernel stack of the context that was interrupted by the wake-up. Prints the count of wake-ups
that waited more than 1, 2 and 5 ms for the CPU and, for the longest, the task that held it and
where it was: "user mode" (then only a higher priority or the hypervisor could delay a FIFO
thread) or a kernel path (on a kernel whose preemption model is "none", a FIFO thread waits
for the kernel code of the task before it: freeing a large process's page tables at its exit,
a page fault, a kernel thread's scan).

    sudo /usr/bin/python3 dev/trace_wakeup_latency.py PID [--duration 120] [--top 10] [--save FILE]

Needs root and tracefs (mounted at /sys/kernel/tracing when it is not). Leaves the tracing
state as it found it: events off, trigger removed, buffer cleared. docs/performance.md
("Real time on a busy machine") has what it found on the development machines.
"""
import argparse
import collections
import os
import re
import subprocess
import sys
import time

TRACING = '/sys/kernel/tracing'
LINE = re.compile(r'^\s*(.+?)-(\d+)\s+\[(\d+)\]\s+\S+\s+([\d.]+): (.*)$')
# Frames of the wake-up itself (timer interrupt, try_to_wake_up): what lies below them is the
# interrupted context.
INTERRUPT_FRAME = 'asm_sysvec_apic_timer_interrupt'


def write(name, text):
    with open(os.path.join(TRACING, name), 'w') as f:
        f.write(text)


def fifo_threads(pid):
    """{tid: (name, priority)} of the process's threads scheduled SCHED_FIFO."""
    threads = {}
    for tid in os.listdir('/proc/%d/task' % pid):
        with open('/proc/%d/task/%s/stat' % (pid, tid)) as f:
            stat = f.read()
        fields = stat[stat.rindex(')') + 2:].split()
        policy, rt_priority = int(fields[38]), int(fields[37])
        if policy == 1:  # SCHED_FIFO
            threads[int(tid)] = (stat[stat.index('(') + 1:stat.rindex(')')], rt_priority)
    return threads


def record(tids, duration_s):
    """The trace text of duration_s seconds: sched_waking (with the waker's stack for the
    threads' wake-ups) and sched_switch of the threads."""
    if not os.path.exists(os.path.join(TRACING, 'trace')):
        subprocess.run(['mount', '-t', 'tracefs', 'nodev', TRACING], check=True)
    condition = ' || '.join('pid == %d' % t for t in tids)
    write('tracing_on', '0')
    write('trace', '')
    write('buffer_size_kb', '65536')
    write('set_event_pid', ' '.join(str(t) for t in tids))
    write('set_event', 'sched:sched_switch\nsched:sched_waking\n')
    write('events/sched/sched_waking/trigger', 'stacktrace if %s' % condition)
    try:
        write('tracing_on', '1')
        time.sleep(duration_s)
        write('tracing_on', '0')
        with open(os.path.join(TRACING, 'trace')) as f:
            return f.read()
    finally:
        write('tracing_on', '0')
        write('events/sched/sched_waking/trigger', '!stacktrace if %s' % condition)
        write('set_event', '')
        write('set_event_pid', '')
        write('trace', '')


def wakeup_delays(text, tids):
    """[(delay_s, thread, waker, interrupted frames or None)] per wake-up of one of the threads: from
    its sched_waking to the sched_switch that gave it the CPU. A wake-up whose switch-in is not
    in the trace (the thread is seen leaving the CPU first) is left out."""
    lines = text.splitlines()
    pending, delays = {}, []
    for i, line in enumerate(lines):
        m = LINE.match(line)
        if not m:
            continue
        body, when = m.group(5), float(m.group(4))
        if body.startswith('sched_waking:'):
            tid = int(re.search(r' pid=(\d+)', body).group(1))
            if tid in tids and tid not in pending:
                pending[tid] = (when, m.group(1), stack_after(lines, i, m.group(2)))
        elif body.startswith('sched_switch:'):
            leaving = int(re.search(r'prev_pid=(\d+)', body).group(1))
            pending.pop(leaving, None)
            tid = int(re.search(r'next_pid=(\d+)', body).group(1))
            if tid in pending:
                woken, waker, frames = pending.pop(tid)
                delays.append((when - woken, tid, waker, frames))
    return delays


def stack_after(lines, i, waker_pid):
    """The frames below the interrupt of the stack trace the trigger wrote after line i."""
    for j in range(i + 1, min(i + 400, len(lines))):
        m = LINE.match(lines[j])
        if m and m.group(2) == waker_pid and m.group(5).startswith('<stack trace>'):
            frames = []
            for k in range(j + 1, len(lines)):
                if not lines[k].lstrip().startswith('=>'):
                    break
                frames.append(lines[k].strip()[3:])
            if INTERRUPT_FRAME in frames:  # a timer's wake-up: what it interrupted on that CPU
                return frames[frames.index(INTERRUPT_FRAME) + 1:] or ['user mode']
            return None  # woken by another thread (a futex): its CPU is not the one waited for
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('pid', type=int, help='the process whose SCHED_FIFO threads are traced')
    parser.add_argument('--duration', type=float, default=120.0, help='seconds to record (default 120)')
    parser.add_argument('--top', type=int, default=10, help='longest delays to list (default 10)')
    parser.add_argument('--save', default=None, help='also write the raw trace to this file')
    args = parser.parse_args()
    if os.geteuid() != 0:
        sys.exit('needs root (tracefs)')
    if not args.duration > 0:
        sys.exit('--duration must be > 0')
    try:
        threads = fifo_threads(args.pid)
    except OSError as e:
        sys.exit('process %d: %s' % (args.pid, e))
    if not threads:
        sys.exit('process %d has no SCHED_FIFO thread (is the node running in real time?)' % args.pid)
    print('tracing %s for %.0f s' % (', '.join('%d (FIFO %d)' % (t, p) for t, (_, p) in threads.items()),
                                     args.duration), flush=True)
    text = record(list(threads), args.duration)
    if args.save:
        with open(args.save, 'w') as f:
            f.write(text)
    delays = wakeup_delays(text, set(threads))
    if not delays:
        sys.exit('no wake-up recorded')
    delays.sort(key=lambda d: -d[0])
    print('%d wake-ups; waited for the CPU more than 1 ms: %d, 2 ms: %d, 5 ms: %d; longest %.1f ms' % (
        len(delays), sum(d[0] > 1e-3 for d in delays), sum(d[0] > 2e-3 for d in delays),
        sum(d[0] > 5e-3 for d in delays), 1e3 * delays[0][0]))
    for delay, tid, waker, frames in delays[:args.top]:
        if frames is None:
            print('%7.1f ms  thread %d, woken by %s, not from a timer interrupt' % (1e3 * delay, tid, waker))
        else:
            print('%7.1f ms  thread %d, timer wake-up, CPU held by %s in %s' % (1e3 * delay, tid, waker,
                                                                                ' < '.join(frames[:8])))
    paths = collections.Counter(d[3][-1] for d in delays if d[0] > 1e-3 and d[3] is not None)
    print('timer wake-ups delayed > 1 ms, by the entry of the interrupted context:',
          ', '.join('%s %d' % (p, n) for p, n in paths.most_common()) or 'none')


if __name__ == '__main__':
    main()
