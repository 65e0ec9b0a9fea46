"""The output files of bearing_sim.cwru_benchmark (records.csv, summary.json, summary.md) and
the summary lines it prints."""
import csv
import json
import math
import pathlib

from bearing_sim.cwru_scoring import COUNT_KEYS, RULES

SERIES = ('BPFO', 'BPFI', '2xBSF', 'FTF')
COLUMNS = (['record', 'file', 'sample_rate_hz', 'channel', 'fault', 'size_in', 'position', 'load_hp', 'rpm',
            'rpm_source', 'smith_randall_best', 'smith_randall_group', 'outcome', 'kinds', 'class', 'right_alone',
            'wrong_named', 'cannot_tell', 'verdict_source', 'verdict_text', 'health', 'kurtosis', 'envelope_band_hz']
           + [f'{s}_{c}' for s in SERIES for c in ('h1_snr_db', 'h2_snr_db', 'h3_snr_db', 'suspected', 'note')]
           + ['variable', 'notes', 'error'])
SOURCES = """\
Data: CWRU Bearing Data Center, Case Western Reserve University,
https://engineering.case.edu/bearingdatacenter (each record's own end: drive-end channel and
bearing, or fan-end channel and bearing for the fan-end set; in g, x 9.80665).
Grades: W. A. Smith and R. B. Randall, Rolling element bearing diagnostics using the Case
Western Reserve University data: a benchmark study, Mechanical Systems and Signal Processing
64-65 (2015) 100-131, Table B2 (their best method; Y clearly, P partially, N not diagnosable).
"""


def write(out_dir, rows, summary):
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    with open(out / 'records.csv', 'w', encoding='utf-8', newline='') as f:
        writer = csv.DictWriter(f, COLUMNS, restval='', extrasaction='ignore')
        writer.writeheader()
        writer.writerows(rows)
    (out / 'summary.json').write_text(json.dumps(summary, indent=1) + '\n', encoding='utf-8')
    (out / 'summary.md').write_text(markdown(rows, summary), encoding='utf-8')


def _fault_name(fault):
    return 'normal' if fault == 'none' else fault


def _cannot_tell(c):
    return c['cannot_tell_truth_among'] + c['cannot_tell_truth_not_among']


def describe(c):
    """One line of counts (cwru_scoring.counts)."""
    text = (f"right type alone {c['right_alone']}, wrong type named {c['wrong_named']}, cannot tell {_cannot_tell(c)} "
            f"(truth among them {c['cannot_tell_truth_among']}, not among {c['cannot_tell_truth_not_among']}), "
            f"nothing found {c['none']}")
    return text + (f", errors {c['errors']}" if c['errors'] else '')


def summary_lines(summary):
    lines = [f"window: {summary['window_s'] or 'whole record'}{' s' if summary['window_s'] else ''}"]
    for title, key in (('all records', 'all'), ('fan-end records (6203, counted apart)', 'fan_end'),
                       ('graded SKF records (Smith & Randall)', 'graded_skf')):
        for fault, c in summary.get(key, {}).items():
            name = title if fault == 'all' else f'  {_fault_name(fault)}'
            lines.append(f"{name} ({c['records']}): {describe(c)}")
    for group, c in summary['smith_randall_groups'].items():
        lines.append(f"Smith & Randall group {group}: right type alone {c['right_alone']} / {c['records']}, "
                     f"wrong type named {c['wrong_named']}, cannot tell {_cannot_tell(c)}")
    g = summary['graded_skf']['all']
    n = g['records']
    lines.append(f"graded SKF records: right type alone {g['right_alone']} / {n}, "
                 f"wrong type named {g['wrong_named']} / {n}, cannot tell {_cannot_tell(g)} / {n}"
                 + (f", errors {g['errors']} / {n}" if g['errors'] else ''))
    return lines


def _table(header, rows):
    lines = ['| ' + ' | '.join(header) + ' |', '|' + '---|' * len(header)]
    return lines + ['| ' + ' | '.join(str(v) for v in row) + ' |' for row in rows]


def _db(value):
    return str(round(value)) if value != '' and math.isfinite(value) else '-'


def _evidence_cell(row, series):
    """'h1/h2/h3' SNR in dB, bold when the series is suspected."""
    text = '/'.join(_db(row.get(f'{series}_h{i}_snr_db', '')) for i in (1, 2, 3))
    return f'**{text}**' if row.get(f'{series}_suspected') else text


def markdown(rows, summary):
    out = ['### CWRU benchmark', '', SOURCES, f"Window: {summary['window_s'] or 'the whole record'}"
           f"{' s' if summary['window_s'] else ''}.", '', '#### Counts', '']
    named = [(title if fault == 'all' else f'{title}: {_fault_name(fault)}', c)
             for title, key in (('all', 'all'), ('fan end', 'fan_end'), ('graded SKF', 'graded_skf'))
             for fault, c in summary.get(key, {}).items()]
    named += [(f'Smith & Randall {group}', c) for group, c in summary['smith_randall_groups'].items()]
    out += _table(['records', 'n', 'right type alone', 'wrong type named', 'cannot tell, truth among',
                   'cannot tell, truth not among', 'nothing found', 'errors'],
                  [[name] + [c[k] for k in COUNT_KEYS] for name, c in named])
    m = summary['confusion']
    out += ['', '#### Confusion matrix (rows: truth, columns: class)', '']
    out += _table(['truth \\ class'] + m['columns'], [[t] + counts for t, counts in zip(m['rows'], m['counts'])])
    out += ['', '#### Records', '', 'Envelope SNR of harmonics 1/2/3 in dB; bold: the series is suspected.', '']
    record_rows = []
    for r in rows:
        size = f"{r['size_in']:.3f}" if r['size_in'] != '' else ''
        rpm = f"{r['rpm']:.0f} ({r['rpm_source']})" if r.get('rpm') else ''
        verdict = r['error'] or r['class']
        record_rows.append([r['record'], f"{r['sample_rate_hz'] / 1000:g}", _fault_name(r['fault']), size,
                            r['position'], r['load_hp'], rpm, r['smith_randall_best'], verdict,
                            r.get('right_alone', ''), r.get('wrong_named', ''), r.get('cannot_tell', '')]
                           + [_evidence_cell(r, s) if not r['error'] else '' for s in SERIES])
    out += _table(['record', 'kHz', 'fault', 'size (in)', 'position', 'load (hp)', 'rpm', 'S&R', 'class',
                   'right alone', 'wrong named', 'cannot tell'] + list(SERIES), record_rows)
    return '\n'.join(out + ['', '#### ' + RULES.replace('Scoring:\n', 'Scoring\n\n'), ''])
