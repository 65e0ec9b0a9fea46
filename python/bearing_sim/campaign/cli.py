"""bearing_campaign: runs a dataset campaign (docs/datasets.md, "Campaigns").
Exit status: 0 every requested run finished, 1 some failed (recorded in the manifest),
2 bad command line, campaign file or output directory (also one that stops taking files,
a full disk, during the runs)."""
import argparse
import os
import sys

from .errors import CampaignError
from .execute import parse_index_range, run_campaign
from .spec import Campaign
from .store import RunStore


def parser():
    p = argparse.ArgumentParser(
        prog='bearing_campaign',
        description='Generates the runs of a dataset campaign: one NPY or HDF5 file per run and a manifest, '
                    'resumable (finished runs are skipped), on Dask distributed.')
    p.add_argument('campaign', help='campaign file (YAML)')
    p.add_argument('--out', required=True, help='output directory (created; a rerun resumes it)')
    p.add_argument('--index-range', metavar='A:B', help='only runs A..B-1 (one task of a job array)')
    where = p.add_mutually_exclusive_group()
    where.add_argument('--workers', type=int, metavar='N',
                       help='local Dask cluster of N single-threaded worker processes (default: the cores '
                            'this process may use)')
    where.add_argument('--scheduler', metavar='tcp://HOST:PORT', help='a running Dask scheduler')
    where.add_argument('--serial', action='store_true', help='in this process, one run after another, no Dask')
    p.add_argument('--manifest-only', action='store_true',
                   help='only rebuild manifest.csv from the runs present (after a job array)')
    p.add_argument('--quiet', action='store_true', help='no progress lines')
    return p


def main(argv=None):
    args = parser().parse_args(argv)
    log = (lambda line: None) if args.quiet else (lambda line: print(line, file=sys.stderr, flush=True))
    try:
        if args.workers is not None and args.workers < 1:
            raise CampaignError(f'--workers: must be >= 1, got {args.workers}')
        campaign = Campaign.load(args.campaign)
        if args.manifest_only:
            store = RunStore(args.out, campaign)
            store.prepare()
            rows, ok = store.write_manifest()
            log(f'campaign {campaign.name}: manifest of {rows} run(s), {ok} finished, {campaign.count - ok} not')
            return 0
        indices = parse_index_range(args.index_range, campaign.count) if args.index_range else None
        summary = run_campaign(campaign, args.out, indices=indices, scheduler=args.scheduler, workers=args.workers,
                               serial=args.serial, log=log)
    except CampaignError as e:
        print(f'bearing_campaign: {e}', file=sys.stderr)
        return 2
    except OSError as e:
        print(f'bearing_campaign: {e}', file=sys.stderr)
        return 2
    return 0 if summary['failed'] == 0 else 1


if __name__ == '__main__':
    sys.exit(main())
