"""Benchmark of the analyser on real data: the Case Western Reserve University (CWRU) bearing
records (normal baseline, 12 kHz and 48 kHz drive-end faults), each record's verdict scored
against its known fault and against Smith & Randall's grades (docs/python.md, "Real data:
the CWRU benchmark").

    python3 -m bearing_sim.cwru_benchmark DIR --out OUTDIR [--window-s S] [--records 105,130]

DIR holds the .mat files as the CWRU Bearing Data Center publishes them
(https://engineering.case.edu/bearingdatacenter; not shipped with this package), named by
their record number ('105.mat') or descriptively ('12k_Drive_End_IR007_0_105.mat'): the
record number is the last number in the name. Each record of config/cwru/records.csv found
there is analysed at the file's shaft speed (its RPM variable, else the table's nominal speed for
its load): a drive-end record's drive-end channel (g -> m/s^2) with
config/bearings/cwru_6205_drive_end.yaml, a fan-end record's fan-end channel with
config/bearings/cwru_6203_fan_end.yaml. The fan-end set is counted apart: nothing of the
analyser was set on it.

Writes into OUTDIR: records.csv (a row per record: metadata, Smith & Randall's grade, the
verdict and its class and scores, the evidence of BPFO, BPFI, 2xBSF and FTF), summary.json
(the counts and the confusion matrix) and summary.md (the same as Markdown tables). Prints
the counts, ending with the line on Smith & Randall's 52 graded SKF records. Exit 2 when DIR
is missing or holds no record of the table.

Smith & Randall: W. A. Smith and R. B. Randall, Rolling element bearing diagnostics using
the Case Western Reserve University data: a benchmark study, Mechanical Systems and Signal
Processing 64-65 (2015) 100-131, Table B2 (config/cwru/smith_randall_2015_table_b2.csv).

Scoring: bearing_sim.cwru_scoring.RULES, printed at the end of --help.
"""
import argparse
import collections
import math
import pathlib
import sys

import bearing_sim
from bearing_sim import cwru_records, cwru_report, cwru_scoring
from bearing_sim.config_files import config_file

BEARING_FILES = {'DE': 'bearings/cwru_6205_drive_end.yaml', 'FE': 'bearings/cwru_6203_fan_end.yaml'}  # per channel


def evidence(result):
    """Per series: SNR of harmonics 1-3 (dB), suspected, note."""
    columns = {}
    by_label = {f['label']: f for f in result['faults']}
    for label in cwru_report.SERIES:
        f = by_label.get(label, {})
        snrs = [h[1] for h in f.get('harmonics', [])][:3]
        for i in range(3):
            columns[f'{label}_h{i + 1}_snr_db'] = round(snrs[i], 1) if i < len(snrs) else ''
        columns[f'{label}_suspected'] = int(f.get('suspected', False))
        columns[f'{label}_note'] = f.get('note', '')
    return columns


def analyse_record(path, meta, grade, bearing, window_s):
    """The row of one record file; an error row when it cannot be read or analysed."""
    row = {'record': meta['record'], 'file': path.name, 'sample_rate_hz': int(meta['sample_rate_hz']),
           'channel': meta['channel'], 'fault': meta['fault'], 'size_in': meta['size_in'] or '',
           'position': meta['position'], 'load_hp': meta['load_hp'], 'smith_randall_best': grade.get('best', ''),
           'smith_randall_group': grade.get('group', ''), 'error': ''}
    try:
        record = cwru_records.load_record(path, meta)
        row.update(rpm=record['rpm'], rpm_source=record['rpm_source'], variable=record['variable'])
        result = bearing_sim.analyze(record['signal'], meta['sample_rate_hz'], bearing,
                                     inner_rad_s=2.0 * math.pi * record['rpm'] / 60.0, window_s=window_s)
        verdict = cwru_scoring.verdict_of(result)
        row.update(outcome=verdict['outcome'], kinds=' + '.join(verdict['kinds']), verdict_source=verdict['source'],
                   verdict_text=verdict['text'], **cwru_scoring.score(meta['fault'], verdict),
                   health=result['health'], kurtosis=round(result['kurtosis'], 2),
                   envelope_band_hz='-'.join(f'{f:.0f}' for f in result['envelope_band_hz']), **evidence(result))
        row['notes'] = '; '.join(record['notes'])
    except Exception as e:  # a bad file is a row of the report, not the end of the run
        row['error'] = f'{type(e).__name__}: {e}'
    return row


def record_numbers(text):
    """'105,130' -> {105, 130} (argparse type)."""
    try:
        return {int(r) for r in text.split(',') if r.strip()}
    except ValueError:
        raise argparse.ArgumentTypeError(f'not a comma-separated list of record numbers: {text!r}') from None


def parser():
    p = argparse.ArgumentParser(prog='python3 -m bearing_sim.cwru_benchmark',
                                description=__doc__.split('\n\n')[0],
                                epilog=cwru_scoring.RULES, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('directory', type=pathlib.Path, help='directory of CWRU .mat files (searched recursively)')
    p.add_argument('--out', type=pathlib.Path, required=True, help='output directory (created)')
    p.add_argument('--window-s', type=float, default=0.0,
                   help='analyse the last S seconds of each record (default 0: the whole record)')
    p.add_argument('--records', type=record_numbers,
                   help='comma-separated record numbers to analyse (default: all found)')
    return p


def main(argv=None):
    args = parser().parse_args(argv)
    if not args.directory.is_dir():
        print(f'cwru_benchmark: {args.directory}: no such directory', file=sys.stderr)
        return 2
    try:
        table, grades = cwru_records.metadata(), cwru_records.smith_randall()
        bearing_files = {channel: config_file(f) for channel, f in BEARING_FILES.items()}
    except FileNotFoundError as e:  # an incomplete installation
        print(f'cwru_benchmark: {e}', file=sys.stderr)
        return 2
    found, skipped = cwru_records.find_records(args.directory, table, args.records)
    for reason, count in collections.Counter(reason for _, reason in skipped).items():
        print(f'skipped {count} file(s): {reason}', file=sys.stderr)
    if not found:
        print(f'cwru_benchmark: {args.directory}: no .mat file of a record in the metadata table '
              f'(config/cwru/records.csv){" among --records" if args.records else ""}', file=sys.stderr)
        return 2
    bearings = {channel: bearing_sim.load_bearing(f) for channel, f in bearing_files.items()}
    rows, warnings = [], []
    for i, (number, path) in enumerate(found, 1):
        meta = table[number]
        warning = cwru_records.rate_warning(path.name, meta)
        if warning:
            warnings.append(warning)
            print(f'warning: {warning}', file=sys.stderr)
        row = analyse_record(path, meta, grades.get(number, {}), bearings[meta['channel']], args.window_s)
        row['notes'] = '; '.join(n for n in (warning, row.get('notes', '')) if n)
        rows.append(row)
        print(f"[{i}/{len(found)}] {number} {meta['fault']}: "
              f"{row['error'] or row['class'] + ' (' + row['verdict_text'] + ')'}", file=sys.stderr)
    summary = cwru_scoring.summarise(rows)
    summary.update(window_s=args.window_s, skipped_files=[{'file': f, 'reason': r} for f, r in skipped],
                   warnings=warnings)
    cwru_report.write(args.out, rows, summary)
    print('\n'.join(cwru_report.summary_lines(summary)))
    return 0


if __name__ == '__main__':
    sys.exit(main())
