"""The output directory of a campaign: one data file and one status record per run under
runs/, the campaign's definition, and the manifest table. Every file is written under a
temporary name and renamed, so a file under its final name is complete; a run is finished
only when its status record says so and its data file has the recorded size."""
import csv
import glob
import io
import json
import os
import shutil
import socket

from .errors import CampaignError

_STAMP = 'campaign.json'


def write_atomically(path, data):
    """Writes bytes to a temporary name beside `path`, flushes them to disk and renames."""
    tmp = os.path.join(os.path.dirname(path), f'.{os.path.basename(path)}.{socket.gethostname()}.{os.getpid()}.tmp')
    try:
        with open(tmp, 'wb') as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


class RunStore:
    def __init__(self, out_dir, campaign):
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

    def is_finished(self, index):
        status = self.read_status(index)
        if not status or status.get('status') != 'ok':
            return False
        try:
            return os.path.getsize(self.data_path(index)) == status.get('bytes')
        except OSError:
            return False

    def remove_leftovers(self, index):
        """Temporary files of an earlier attempt at run i that was killed (never another run's)."""
        for path in glob.glob(os.path.join(self.runs_dir, f'.run_{index:07d}.*.tmp')):
            if os.path.isdir(path):
                shutil.rmtree(path, ignore_errors=True)
            elif os.path.exists(path):
                os.remove(path)

    def write_status(self, index, record):
        write_atomically(self.status_path(index), (json.dumps(record, indent=1, default=str) + '\n').encode())

    def write_manifest(self):
        """manifest.csv: one row per run with a status record (ok or failed), in index order:
        index, status, file, seed, error, the parameters and the labels. Rebuilt from the
        records, so concurrent job-array tasks never write one file together."""
        records = []
        for path in sorted(glob.glob(os.path.join(self.runs_dir, 'run_*.json'))):
            try:
                with open(path, encoding='utf-8') as f:
                    records.append(json.load(f))
            except (OSError, ValueError):
                continue
        parameter_names = list(self.campaign.parameters)
        label_names = sorted({k for r in records for k in (r.get('labels') or {})})
        out = io.StringIO()
        w = csv.writer(out, lineterminator='\n')
        w.writerow(['index', 'status', 'file', 'seed', 'error'] + [f'param_{n}' for n in parameter_names]
                   + [f'label_{n}' for n in label_names])
        for r in records:
            finished = r.get('status') == 'ok' and self.is_finished(r['index'])
            params = r.get('parameters') or {}
            labels = r.get('labels') or {}
            status = 'ok' if finished else r.get('status', 'failed')
            error = r.get('error', '')
            if status == 'ok' and not finished:  # the data file went missing or was cut short
                status, error = 'incomplete', 'data file missing or not of the recorded size'
            w.writerow([r['index'], status, r.get('file', '') if finished else '', r.get('seed', ''), error]
                       + [_cell(params.get(n)) for n in parameter_names] + [_cell(labels.get(n)) for n in label_names])
        write_atomically(os.path.join(self.out_dir, 'manifest.csv'), out.getvalue().encode())
        return records


def _cell(value):
    if isinstance(value, (dict, list)):
        return json.dumps(value, sort_keys=True)
    return '' if value is None else value
