"""The Case Western Reserve University (CWRU) bearing records on disk: the metadata table
(config/cwru/records.csv), Smith & Randall's grades (config/cwru/smith_randall_2015_table_b2.csv),
the record files in a directory, and one record's signal and speed. Used by
bearing_sim.cwru_benchmark."""
import csv
import math
import pathlib
import re

from bearing_sim.config_files import config_file

G = 9.80665  # m/s^2 per g: CWRU's accelerometer channels are in g


def read_table(path):
    """Rows (dicts of strings) of a CSV file whose leading '#' lines are comments."""
    with open(path, encoding='utf-8', newline='') as f:
        return list(csv.DictReader(line for line in f if not line.startswith('#')))


def metadata(path=None):
    """{record: its row}, in the table's order, with numbers as numbers."""
    table = {}
    for row in read_table(path or config_file('cwru/records.csv')):
        row.update(record=int(row['record']), sample_rate_hz=float(row['sample_rate_hz']),
                   size_in=float(row['size_in']) if row['size_in'] else None, load_hp=int(row['load_hp']),
                   nominal_rpm=float(row['nominal_rpm']))
        table[row['record']] = row
    return table


def smith_randall(path=None):
    """{record: {'m1', 'm2', 'm3', 'best', 'group'}} of Smith & Randall's Table B2."""
    return {int(row.pop('record')): row
            for row in read_table(path or config_file('cwru/smith_randall_2015_table_b2.csv'))}


def record_number(file_name):
    """CWRU's record number: the last number in the name ('12k_Drive_End_OR007@6_0_130.mat',
    '130.mat': 130), or None."""
    numbers = re.findall(r'\d+', pathlib.Path(file_name).stem)
    return int(numbers[-1]) if numbers else None


def name_rate_hz(file_name):
    """The sample rate a name's prefix states ('12k_...', '48k_...'), or None."""
    m = re.match(r'(12|48)k[_\- ]', pathlib.Path(file_name).name, re.IGNORECASE)
    return float(m.group(1)) * 1000.0 if m else None


def rate_warning(file_name, meta):
    """A warning when the name's sample-rate prefix disagrees with the table (the table wins)."""
    rate = name_rate_hz(file_name)
    if rate is None or rate == meta['sample_rate_hz']:
        return ''
    return (f"{pathlib.Path(file_name).name}: the name says {rate / 1000:g} kHz, the table "
            f"{meta['sample_rate_hz'] / 1000:g} kHz for record {meta['record']}; using the table's")


def find_records(directory, table, wanted=None):
    """The record files under `directory` (searched recursively): ([(record, path)] in the
    table's order, [(file name, why skipped)]). `wanted`: record numbers to keep."""
    found, notes = {}, []
    for path in sorted(pathlib.Path(directory).rglob('*.mat')):
        record = record_number(path.name)
        if record is None:
            notes.append((path.name, 'no record number in the name'))
        elif record not in table:
            notes.append((path.name, 'not a record of the metadata table'))
        elif wanted and record not in wanted:
            continue
        elif record in found:
            notes.append((path.name, f'record {record} already read from {found[record].name}'))
        else:
            found[record] = path
    return [(r, found[r]) for r in table if r in found], notes


def load_record(path, meta):
    """One record file (MATLAB v5, as CWRU publishes them): {'signal' (m/s^2), 'variable',
    'rpm', 'rpm_source' ('file' or 'table'), 'notes'}."""
    import numpy as np
    import scipy.io
    data = scipy.io.loadmat(str(path))
    channel = meta['channel']
    variable = f"X{meta['record']:03d}_{channel}_time"
    notes = []
    if variable not in data:
        # Some published files name their variables after another number (the 0.028 in
        # records hold X048..X059, 174 holds X173): take the file's only channel of this end.
        others = sorted(k for k in data if re.fullmatch(rf'X\d+_{channel}_time', k))
        if len(others) != 1:
            variables = sorted(k for k in data if not k.startswith('__'))
            raise ValueError(f'no variable {variable}; the file has {variables}')
        notes.append(f'signal from {others[0]} (the file has no {variable})')
        variable = others[0]
    signal = np.asarray(data[variable], dtype=float).ravel() * G
    if signal.size == 0 or not np.all(np.isfinite(signal)):
        raise ValueError(f'{variable} is empty or not finite')
    rpm_variable = variable[:-len(f'_{channel}_time')] + 'RPM'
    rpm = math.nan
    if rpm_variable in data:
        values = np.asarray(data[rpm_variable], dtype=float).ravel()
        rpm = float(values[0]) if values.size else math.nan
    if math.isfinite(rpm) and rpm > 0.0:
        return dict(signal=signal, variable=variable, rpm=rpm, rpm_source='file', notes=notes)
    if rpm_variable in data:
        notes.append(f'{rpm_variable} = {rpm:g} unusable: the table speed is used')
    return dict(signal=signal, variable=variable, rpm=meta['nominal_rpm'], rpm_source='table', notes=notes)
