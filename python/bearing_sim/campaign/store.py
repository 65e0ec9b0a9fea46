"""The output directory of a campaign: one data file and one status record per run under
runs/, the campaign's definition, and the manifest table. Every file is written under a
temporary name and renamed, so a file under its final name is complete; a run is finished
only when its status record says so and its data file has the recorded size. A file that
cannot be written is an OutputError naming it."""
import contextlib
import csv
import glob
import io
import json
import os
import re
import shutil
import socket

from .errors import CampaignError, OutputError
from .run_files import LABEL_NAMES

_STAMP = 'campaign.json'
_STATUS_NAME = re.compile(r'run_(\d+)\.json')


@contextlib.contextmanager
def atomic_file(path):
    """A binary file written under a temporary name beside `path`, flushed to disk and renamed
    to `path` when the block ends without an error, removed otherwise."""
    tmp = os.path.join(os.path.dirname(path), f'.{os.path.basename(path)}.{socket.gethostname()}.{os.getpid()}.tmp')
    try:
        with open(tmp, 'wb') as f:
            yield f
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except OSError as e:  # a full disk, a read-only or vanished directory
        raise OutputError(f'cannot write {path}: {e.strerror or e}') from None
    finally:
        with contextlib.suppress(OSError):
            os.remove(tmp)


def write_atomically(path, data):
    with atomic_file(path) as f:
        f.write(data)


class RunStore:
    def __init__(self, out_dir, campaign):
        if not os.fspath(out_dir):
            raise CampaignError('--out: empty; give the output directory')
        self.out_dir = os.path.abspath(out_dir)
        self.runs_dir = os.path.join(self.out_dir, 'runs')
        self.campaign = campaign
        self.extension = '.npy' if campaign.format == 'npy' else '.h5'

    def prepare(self):
        """Creates the directory, or checks that it holds this same campaign (a different one
        would mix runs of two definitions under one manifest)."""
        try:
            os.makedirs(self.runs_dir, exist_ok=True)
        except OSError as e:
            raise CampaignError(f'--out {self.out_dir}: cannot create the directory: {e.strerror}') from None
        if not os.access(self.runs_dir, os.W_OK):
            raise CampaignError(f'--out {self.out_dir}: the directory is not writable')
        stamp = os.path.join(self.out_dir, _STAMP)
        mine = {'name': self.campaign.name, 'count': self.campaign.count,
                'definition_sha256': self.campaign.definition_sha256, 'campaign_file': self.campaign.path}
        if os.path.exists(stamp):
            with open(stamp, encoding='utf-8') as f:
                theirs = json.load(f)
            if theirs.get('definition_sha256') != mine['definition_sha256']:
                raise CampaignError(f"--out {self.out_dir}: holds the runs of another campaign definition "
                                    f"('{theirs.get('name')}' from {theirs.get('campaign_file')}); "
                                    f'use another directory')
        else:
            write_atomically(stamp, (json.dumps(mine, indent=1) + '\n').encode())
            write_atomically(os.path.join(self.out_dir, 'campaign.yaml'), self.campaign.text.encode())

    def data_path(self, index):
        return os.path.join(self.runs_dir, f'run_{index:07d}{self.extension}')

    def status_path(self, index):
        return os.path.join(self.runs_dir, f'run_{index:07d}.json')

    def read_status(self, index):
        try:
            with open(self.status_path(index), encoding='utf-8') as f:
                return json.load(f)
        except (OSError, ValueError):
            return None

    def _complete(self, status):
        """A record of a finished run: ok, and its data file of the recorded size."""
        if not status or status.get('status') != 'ok':
            return False
        try:
            return os.path.getsize(self.data_path(status['index'])) == status.get('bytes')
        except (OSError, KeyError, TypeError):
            return False

    def is_finished(self, index):
        return self._complete(self.read_status(index))

    def finished_record(self, index):
        """The status record of run `index` if the run is finished, else None."""
        record = self.read_status(index)
        return record if self._complete(record) else None

    def with_status(self, indices):
        """Which of `indices` (a range) have a status record, as one byte per index, from one
        listing of runs/: the work is that of the files present, not of the campaign's count."""
        present = bytearray(len(indices))
        with os.scandir(self.runs_dir) as entries:
            for entry in entries:
                match = _STATUS_NAME.fullmatch(entry.name)
                if match and int(match.group(1)) in indices:
                    present[int(match.group(1)) - indices.start] = 1
        return present

    def finished(self, indices):
        """Which of `indices` (a range) are finished, one byte per index."""
        done = self.with_status(indices)
        k = done.find(1)
        while k >= 0:
            done[k] = self.is_finished(indices.start + k)
            k = done.find(1, k + 1)
        return done

    def remove_leftovers(self, index):
        """Temporary files of an earlier attempt at run i that was killed (never another run's)."""
        for path in glob.glob(os.path.join(self.runs_dir, f'.run_{index:07d}.*.tmp')):
            if os.path.isdir(path):
                shutil.rmtree(path, ignore_errors=True)
            elif os.path.exists(path):
                os.remove(path)

    def write_status(self, index, record):
        write_atomically(self.status_path(index), (json.dumps(record, indent=1, default=str) + '\n').encode())

    def records(self):
        """The status records present, in index order, read one at a time."""
        indices = range(self.campaign.count)
        present = self.with_status(indices)
        k = present.find(1)
        while k >= 0:
            record = self.read_status(k)
            if record is not None:
                yield record
            k = present.find(1, k + 1)

    def write_manifest(self):
        """manifest.csv: one row per run with a status record (ok or failed), in index order:
        index, status, file, seed, error, the parameters and the labels. Rebuilt from the
        records, so concurrent job-array tasks never write one file together; written row by
        row, so its size is not held in memory. Returns (rows, finished runs)."""
        parameter_names = list(self.campaign.parameters)
        rows = finished_count = 0
        with atomic_file(os.path.join(self.out_dir, 'manifest.csv')) as f:
            text = io.TextIOWrapper(f, encoding='utf-8', newline='')
            w = csv.writer(text, lineterminator='\n')
            w.writerow(['index', 'status', 'file', 'seed', 'error'] + [f'param_{n}' for n in parameter_names]
                       + [f'label_{n}' for n in LABEL_NAMES])
            for r in self.records():
                finished = self._complete(r)
                params = r.get('parameters') or {}
                labels = r.get('labels') or {}
                status = 'ok' if finished else r.get('status', 'failed')
                error = r.get('error', '')
                if status == 'ok' and not finished:  # the data file went missing or was cut short
                    status, error = 'incomplete', 'data file missing or not of the recorded size'
                w.writerow([r['index'], status, r.get('file', '') if finished else '', r.get('seed', ''), error]
                           + [_cell(params.get(n)) for n in parameter_names]
                           + [_cell(labels.get(n)) for n in LABEL_NAMES])
                rows += 1
                finished_count += finished
            text.flush()
            text.detach()  # leave the file to atomic_file, which syncs and renames it
        return rows, finished_count


def _cell(value):
    if isinstance(value, (dict, list)):
        return json.dumps(value, sort_keys=True)
    return '' if value is None else value
