"""The output directory has one owner per run: a second bearing_campaign on runs another
process holds is refused (exit 2) naming the lock, while job-array tasks with disjoint index
ranges share the directory. A file that cannot be written (here: beyond RLIMIT_FSIZE, as a
full disk) stops the campaign naming it, with the manifest of the runs finished so far; a
rerun resumes."""
import csv
import os
import resource
import subprocess
import sys
import time

from bearing_sim.campaign.run_lock import RunLock
from conftest import SOURCE, small_campaign

SCRIPT = SOURCE / 'scripts' / 'bearing_campaign'


def bearing_campaign(path, out, *args, preexec_fn=None):
    return subprocess.Popen([sys.executable, str(SCRIPT), str(path), '--out', str(out), '--serial', *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, preexec_fn=preexec_fn)


def finish(process):
    _, err = process.communicate(timeout=300)
    return process.returncode, err


def manifest(out):
    with open(out / 'manifest.csv', newline='') as f:
        return {int(r['index']): r for r in csv.DictReader(f)}


def test_runs_another_process_holds_are_refused_disjoint_ranges_share(campaign_file, tmp_path):
    path = campaign_file(small_campaign(count=20))
    out = tmp_path / 'out'
    out.mkdir()
    # This test process stands for a campaign generating runs 0..9 (fcntl locks are per process).
    with RunLock(str(out), range(0, 10)):
        code, err = finish(bearing_campaign(path, out))
        assert code == 2, err
        assert f'--out {out}: another bearing_campaign process (PID {os.getpid()}) is generating runs of 0..19' in err
        assert f'lock {out}/campaign.lock' in err
        code, err = finish(bearing_campaign(path, out, '--index-range', '5:15'))
        assert code == 2 and 'runs of 5..14' in err, err
        assert not list((out / 'runs').glob('run_*'))
        code, err = finish(bearing_campaign(path, out, '--index-range', '10:20'))
        assert code == 0, err
    assert sorted(manifest(out)) == list(range(10, 20))
    code, err = finish(bearing_campaign(path, out))  # the lock is gone with its holder
    assert code == 0 and '10 run(s) to do, 10 already finished' in err, err


def test_two_campaigns_on_one_out_never_compute_a_run_twice(campaign_file, tmp_path):
    path = campaign_file(small_campaign(count=30, duration_s=2.0))
    out = tmp_path / 'out'
    first = bearing_campaign(path, out)
    deadline = time.monotonic() + 300
    while not list((out / 'runs').glob('run_*.json')) and first.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    second = bearing_campaign(path, out)  # while the first is (most likely) still running
    (code1, err1), (code2, err2) = finish(first), finish(second)
    assert code1 == 0, err1
    # Refused while the first held the runs, or started after it ended and found them finished.
    assert (code2 == 2 and 'another bearing_campaign process' in err2) or \
        (code2 == 0 and '0 run(s) to do, 30 already finished' in err2), err2
    rows = manifest(out)
    assert sorted(rows) == list(range(30)) and {r['status'] for r in rows.values()} == {'ok'}
    assert not list((out / 'runs').glob('.*.tmp'))


def test_a_file_that_cannot_be_written_stops_the_campaign_naming_it(campaign_file, tmp_path):
    doc = small_campaign(count=4)
    # Runs 0 and 1 write 12 kB, run 2 120 kB: beyond the 20 kB file size limit below.
    doc['parameters']['duration_s'] = {'grid': [0.1, 0.1, 1.0, 0.1]}
    doc['scenario']['duration_s'] = '${duration_s}'
    path = campaign_file(doc)
    out = tmp_path / 'out'

    def small_files():  # writing past it fails with EFBIG (Python ignores SIGXFSZ), as a full disk
        resource.setrlimit(resource.RLIMIT_FSIZE, (20000, 20000))
    code, err = finish(bearing_campaign(path, out, preexec_fn=small_files))
    assert code == 2, err
    assert f'cannot write {out}/runs/run_0000002.npy: File too large; the campaign stopped (2 run(s) finished now, ' \
           f'manifest {out}/manifest.csv)' in err, err
    assert 'Traceback' not in err
    rows = manifest(out)
    assert sorted(rows) == [0, 1] and {r['status'] for r in rows.values()} == {'ok'}
    assert not list((out / 'runs').glob('.*.tmp'))
    code, err = finish(bearing_campaign(path, out))
    assert code == 0 and '2 run(s) to do, 2 already finished' in err, err
    assert {r['status'] for r in manifest(out).values()} == {'ok'} and len(manifest(out)) == 4
