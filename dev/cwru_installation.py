#!/usr/bin/python3
"""Measures the CWRU drive-end rig's installation (docs/sensor.md, "The CWRU drive-end
installation") from the real records, so that the numbers of
config/sensors/cwru_drive_end_accelerometer.yaml can be re-derived. A development script:
it reads the CWRU Bearing Data Center's .mat files from a directory given on the command
line (their licence does not allow copying them into this repository) and prints the
derived numbers only.

    python3 dev/cwru_installation.py /work/cwru                    # the installation, as YAML
    python3 dev/cwru_installation.py /work/cwru --compare sim.csv  # real vs simulated table
    python3 dev/cwru_installation.py /work/cwru --slot-comb        # + the fault records' comb level
    python3 dev/cwru_installation.py /work/cwru --rolling-noise    # + the fault records' rolling noise
    python3 dev/cwru_installation.py /work/cwru --mode-spread      # + the path's peaks record by record
    python3 dev/cwru_installation.py /work/cwru --mode-balance     # + its low modes against 2.9 kHz, by assembly

Not executable and not installed: a development script (like cwru_indicators.py, it works on
the source tree).

--compare takes a --sensor-csv of `bearing_tool simulate` (time, x, y, z; x is used) at
12 kHz, in m/s^2 or in g (--compare-unit).

Source: CWRU Bearing Data Center, Case Western Reserve University,
https://engineering.case.edu/bearingdatacenter (records named below).
"""
import argparse
import functools
import pathlib
import re
import sys

import numpy as np
import scipy.io
import scipy.ndimage
import scipy.signal

G = 9.80665
FS = 12000.0
NORMAL = 'normal_0_97.mat'           # 48 kHz, 0 hp, drive-end channel
# The largest seeded faults, inner and outer race, all loads: impacts that ring the path's modes.
MODE_RECORDS = ('IR014', 'IR021', 'OR014@6', 'OR021@6', 'OR021@3', 'OR021@12')
# Where the fault records' spectra show the path's modes (the search windows, Hz).
MODE_WINDOWS = ((950, 1150), (1300, 1500), (2500, 3000), (3200, 3700), (4000, 4400), (5000, 5400))
SHAFT_HARMONICS = 48                 # 1..48 x f_r: the integer orders standing out of the floor
HALF_ORDERS = (0.5, 1.5, 2.5)
LINE_HARMONICS = 6                   # 1..6 x the line frequency
MIN_OTHER_ORDER_MG = 2.0             # other speed-locked orders reported above this
MAX_OTHER_ORDERS = 16
# The sensor's mounted resonance (docs/sensor.md, "The sensor's mount"): the sensor sits on a
# magnetic base, whose contact stiffness under the sensor's mass is a resonance of the sensor
# itself, in series with the structure. The window holding it: the highest peak of the fault
# records' spectra, 3.4 kHz; the other windows' peaks are the structure's modes, each seen
# through the mount (their heights divided by the mount's |T_m(f)|^2).
MOUNT_WINDOW = (3200, 3700)
# The structure's modes carry the whole path at the sensor: their participations, in their
# measured ratios, add up to 1 (the housing follows the ring below them, isolates above). With
# the mount in series this meets the real fault records' 2-4 kHz power without a level of its
# own (median over the 36 fault conditions of dev/cwru_rig_compare.py: -2.8 dB; before the
# mount, the five modes had to add up to 5.6 for it, their residual -4.6 passing 4-6 kHz).
PATH_LEVEL = 1.0
# The fault records' rolling noise (--rolling-noise): the random part of each record's power in
# the band where the path passes it (the mount and the 2.9 kHz mode), read between the impacts:
# the ROLLING_QUANTILE of the band's power over blocks of ROLLING_BLOCK_S, over the same
# quantile's share of the mean for Gaussian noise in that band (~0.6). A race fault's impacts
# ring for ~1 ms once per 6-10 ms, so the lower fifth of 2 ms blocks lies between them.
ROLLING_BAND_HZ = (2000.0, 4000.0)
ROLLING_BLOCK_S = 0.002
ROLLING_QUANTILE = 0.2
# How strongly an assembly's path passes its low modes against the 2.9 kHz one (--mode-balance):
# the power in BALANCE_LOW_HZ over that in BALANCE_HIGH_HZ (modal_density), the median over a
# record's 1 s windows, in the records of every 12 kHz fault condition of 0.007-0.021 in but
# those whose fault the signal does not show (the machine's background fills them:
# docs/cwru_rig.md).
BALANCE_LOW_HZ = (950.0, 1500.0)
BALANCE_HIGH_HZ = (2500.0, 3000.0)
BALANCE_UNSEEN = ('B007', 'OR014@6')
FLOOR_POINTS_HZ = (30, 60, 100, 150, 200, 300, 400, 500, 700, 1000, 1300, 1600, 2000, 2500, 3000,
                   3500, 4000, 4500, 5000, 5500)


def drive_end(path):
    data = scipy.io.loadmat(str(path))
    key = next(k for k in data if k.endswith('_DE_time'))
    rpm = [v for k, v in data.items() if k.endswith('RPM')]
    return data[key].ravel().astype(float), (float(np.ravel(rpm[0])[0]) if rpm else None)


def normal_record(directory):
    x48, rpm = drive_end(directory / NORMAL)
    # 48 kHz -> 12 kHz with a long Kaiser FIR (scipy's polyphase default), as the 12 kHz records.
    return scipy.signal.resample_poly(x48, 1, 4), rpm


def amplitude(x, f_hz, fs=FS):
    """Peak amplitude of the line at f_hz: the Hann-windowed DTFT at that exact frequency
    (no scalloping loss), in the unit of x."""
    n = len(x)
    w = np.hanning(n)
    t = np.arange(n) / fs
    return 2.0 * abs(np.sum((x - x.mean()) * w * np.exp(-2j * np.pi * f_hz * t))) / w.sum()


def best_frequency(x, guess_hz, multipliers, span_hz, steps=201):
    """The base frequency f within guess +- span that maximises the summed power of its
    lines k f, k in multipliers."""
    candidates = np.linspace(guess_hz - span_hz, guess_hz + span_hz, steps)
    power = [sum(amplitude(x, f * k) ** 2 for k in multipliers) for f in candidates]
    return candidates[int(np.argmax(power))]


def shaft_and_line(x, rpm):
    """The shaft rate from its 9th-24th harmonics (the strong integer orders; the file's rpm
    is rounded) and the line frequency from its 2nd, 4th and 6th harmonics."""
    return (best_frequency(x, rpm / 60.0, range(9, 25), 0.02),
            best_frequency(x, 60.0, (2, 4, 6), 0.05))


def welch(x, nperseg):
    return scipy.signal.welch(x, FS, nperseg=nperseg)


def floor_density(x, points_hz):
    """The broadband floor at each point: the median of a Welch PSD (1.5 Hz bins) within
    +-1/6 octave (a third octave) of the point. The median ignores the discrete lines."""
    f, p = welch(x, 8192)
    out = []
    for fc in points_hz:
        band = (f >= fc * 2 ** (-1 / 6)) & (f <= min(fc * 2 ** (1 / 6), 0.5 * FS))
        out.append(float(np.sqrt(np.median(p[band]))))
    return out


def record_statistics(x, f_r, line_hz):
    """RMS, share of the power in discrete lines, main line levels, floor (all in g)."""
    f, p = welch(x, 16384)                   # 0.73 Hz bins: the lines stand clear
    # Floor: a running median over 75 Hz; the share in lines is what stands above it.
    floor = scipy.ndimage.median_filter(p, size=103, mode='nearest')
    share = 1.0 - np.sum(np.minimum(p, floor)) / np.sum(p)
    levels = {
        '1 x f_r': amplitude(x, f_r), '2 x f_r': amplitude(x, 2 * f_r),
        '2 x line': amplitude(x, 2 * line_hz), '6 x line': amplitude(x, 6 * line_hz),
        '5.402 x f_r': amplitude(x, 5.402 * f_r), '138.491 x f_r': amplitude(x, 138.491 * f_r),
    }
    dens = floor_density(x, (500.0, 3000.0))
    return {'rms': float(np.std(x)), 'line_share': float(share), 'levels': levels, 'floor': dens}


def measure_normal(directory):
    x, rpm = normal_record(directory)
    f_r, line = shaft_and_line(x, rpm)
    shaft = [amplitude(x, k * f_r) for k in range(1, SHAFT_HARMONICS + 1)]
    half = [amplitude(x, q * f_r) for q in HALF_ORDERS]
    lines = [amplitude(x, h * line) for h in range(1, LINE_HARMONICS + 1)]
    # Other speed-locked orders: the strongest peaks that are neither k/2 x f_r nor k x line.
    n = len(x)
    spectrum = 2.0 * np.abs(np.fft.rfft((x - x.mean()) * np.hanning(n))) / np.hanning(n).sum()
    freqs = np.fft.rfftfreq(n, 1 / FS)
    peaks, _ = scipy.signal.find_peaks(spectrum, distance=int(2.0 / (FS / n)))
    others = []
    for i in peaks[np.argsort(spectrum[peaks])[::-1]]:
        if spectrum[i] < MIN_OTHER_ORDER_MG * 1e-3 or freqs[i] < 0.4 * f_r:
            continue
        order = freqs[i] / f_r
        # Within 0.25 Hz (1.2 bins) of a half order or of a line harmonic: those series.
        if (abs(order - round(2 * order) / 2) * f_r < 0.25 and round(2 * order) <= 2 * SHAFT_HARMONICS) or \
                abs(freqs[i] / line - round(freqs[i] / line)) * line < 0.25:
            continue
        # Refine the frequency on the exact DTFT (+-one bin).
        fine = np.linspace(freqs[i] - FS / n, freqs[i] + FS / n, 41)
        a = [amplitude(x, v) for v in fine]
        j = int(np.argmax(a))
        others.append((round(fine[j] / f_r, 3), a[j]))
        if len(others) == MAX_OTHER_ORDERS:
            break
    others.sort()
    return x, f_r, line, shaft, half, lines, others, floor_density(x, FLOOR_POINTS_HZ)


def modal_density(x):
    """Welch density of 2048 points with the lines removed, the path's modes kept: a running
    median over 7 bins (41 Hz) removes the lines (3 bins wide), not the modes. (f, density)."""
    f, p = welch(x, 2048)
    return f, scipy.ndimage.median_filter(p, size=7, mode='nearest')

def record_shapes(directory, normal_x):
    """Per MODE_RECORDS record: its Welch density, lines removed, less the normal record's,
    normalised by its power ({record number: density}), and the frequencies."""
    f, p0 = welch(normal_x, 2048)
    shapes = {}
    for path in sorted(directory.glob('12k_Drive_End_*.mat')):
        if not any(f'_{tag}_' in path.name for tag in MODE_RECORDS):
            continue
        x, _ = drive_end(path)
        _, p = modal_density(x)
        shapes[path.stem.rsplit('_', 1)[1]] = np.maximum(p - p0, 1e-16) / np.sum(p)
    return f, shapes


def window_peak(f, shape, lo, hi):
    """The bin of shape's maximum in [lo, hi] Hz and whether it is a mode: a maximum within
    two bins of the window's edge is the flank of a mode outside the window (4.0-4.4 kHz: the
    3.4 kHz mode's flank at 4008 Hz)."""
    inside = np.flatnonzero((f >= lo) & (f <= hi))
    i = inside[np.argmax(shape[inside])]
    return i, inside[1] < i < inside[-2]


def print_mode_spread(f, shapes):
    """How far each window's peak moves from record to record (each assembly's path): its
    10th and 90th percentiles over the records (record_shapes) that show it, against their
    median."""
    for lo, hi in MODE_WINDOWS:
        peaks = [f[i] for i, is_mode in (window_peak(f, v, lo, hi) for v in shapes.values()) if is_mode]
        if not peaks:
            print(f'#   {lo}-{hi} Hz: no record shows a peak inside the window')
            continue
        median = np.median(peaks)
        p10, p90 = np.percentile(peaks, [10, 90])
        print(f'#   {lo}-{hi} Hz: the peak in {len(peaks)} of {len(shapes)} records, median {median:.0f} Hz, '
              f'10th / 90th percentile {100 * (p10 / median - 1):+.1f} / {100 * (p90 / median - 1):+.1f} %')


def measure_modes(f, shapes):
    """The path's modes from the fault records: the geometric mean over records of the
    fault-record PSD (lines removed) less the normal record's, normalised per record (record_shapes;
    impacts excite the path with a nearly flat spectrum: what the path's |H|^2 shapes). In each
    window: the peak's frequency, its half-power width (damping ratio zeta = width / (2 f)) and
    its height."""
    names = list(shapes)
    shape = np.exp(np.mean([np.log(v) for v in shapes.values()], axis=0))
    modes, dropped = [], []
    for lo, hi in MODE_WINDOWS:
        i, is_mode = window_peak(f, shape, lo, hi)
        if not is_mode:
            dropped.append((lo, hi, float(f[i])))
            continue
        half = shape[i] / 2.0
        a, b = i, i
        while a > 0 and shape[a] > half:
            a -= 1
        while b < len(shape) - 1 and shape[b] > half:
            b += 1
        # Linear interpolation of the half-power crossings.
        f_lo = f[a] + (half - shape[a]) / (shape[a + 1] - shape[a]) * (f[a + 1] - f[a])
        f_hi = f[b - 1] + (half - shape[b - 1]) / (shape[b] - shape[b - 1]) * (f[b] - f[b - 1])
        # A width beyond 5 % is the comb or two modes merged: held at 5 %.
        zeta = float(np.clip((f_hi - f_lo) / (2.0 * f[i]), 0.01, 0.05))
        modes.append({'f': float(f[i]), 'zeta': zeta, 'height': float(shape[i])})
    # The mount: the peak in MOUNT_WINDOW, a resonance of participation 1 in series with the
    # structure.
    mount = next(m for m in modes if MOUNT_WINDOW[0] <= m['f'] <= MOUNT_WINDOW[1])
    modes = [m for m in modes if m is not mount]
    # The structure's peak transmissibility p / (2 zeta) proportional to the square root of its
    # height seen through the mount; the sum of p is PATH_LEVEL.
    weights = [m['zeta'] * np.sqrt(m['height']) / abs(seismic(m['f'], mount['f'], mount['zeta'])) for m in modes]
    for m, w in zip(modes, weights):
        m['p'] = float(PATH_LEVEL * w / sum(weights))
    return modes, mount, names, dropped


def seismic(f_hz, resonance_hz, zeta):
    """The seismic transmissibility (2 zeta w s + w^2) / (s^2 + 2 zeta w s + w^2) at f_hz."""
    s, w = 2j * np.pi * f_hz, 2.0 * np.pi * resonance_hz
    return (2.0 * zeta * w * s + w * w) / (s * s + 2.0 * zeta * w * s + w * w)


def print_installation(directory, slot_comb=False, rolling_noise=False, mode_spread=False):
    x, f_r, line, shaft, half, lines, others, floor = measure_normal(directory)
    f, shapes = record_shapes(directory, x)
    modes, mount, names, dropped = measure_modes(f, shapes)
    mg = lambda v: f'{v / 1e-3:.3g}'
    print(f'# From {NORMAL} (record 97, 0 hp): f_r {f_r:.3f} Hz (file: 1796 rpm), line {line:.3f} Hz')
    print(f'# Path modes from records {", ".join(names)}')
    for lo, hi, peak in dropped:
        print(f'# No mode in {lo}-{hi} Hz: its maximum, {peak:.0f} Hz, is at the window\'s edge')
    print(f"  mount_resonance_Hz: {mount['f']:.0f}")
    print(f"  mount_damping_ratio: {mount['zeta']:.3f}")
    print('  path_modes:')
    for m in modes:
        print(f"    - {{frequency_Hz: {m['f']:.0f}, damping_ratio: {m['zeta']:.3f}, participation: {m['p']:.3f}}}")
    print('  installation:')
    print(f'    shaft_harmonics_mg: [{", ".join(mg(v) for v in shaft)}]')
    print(f'    half_orders_mg: [{", ".join(mg(v) for v in half)}]')
    print('    speed_locked_orders:')
    for order, a in others:
        print(f'      - {{order: {order}, amplitude_mg: {mg(a)}}}')
    print(f'    line_frequency_Hz: {line:.2f}')
    if slot_comb:
        levels = slot_comb_levels(directory, others)
        values = np.array(list(levels.values()))
        print(f'    # The slot-harmonic comb (orders > 100) in the {len(values)} 12 kHz fault records against record 97: '
              f'median {np.median(values):.1f} dB, {values.min():.1f} to {values.max():.1f} dB')
    print(f'    line_harmonics_mg: [{", ".join(mg(v) for v in lines)}]')
    if mode_spread:
        print('    # The path\'s peaks record by record (each assembly):')
        print_mode_spread(f, shapes)
    if rolling_noise:
        levels, normal_mg = rolling_noise_levels(directory, modes, mount)
        values = np.array(list(levels.values()))
        print(f'    # The fault records\' rolling noise, white at the ring, ug/sqrt(Hz) (record 97: {normal_mg:.1f} mg '
              f'random in {ROLLING_BAND_HZ[0]:.0f}-{ROLLING_BAND_HZ[1]:.0f} Hz, subtracted): ' +
              ', '.join(f'{r} {v:.0f}' for r, v in levels.items()))
        print(f'    # rolling_noise_ug_per_sqrt_Hz in the {len(values)} fault records: median {np.median(values):.0f}, '
              f'{values.min():.0f} to {values.max():.0f}')
    print('    floor:')
    print(f'      frequencies_Hz: [{", ".join(str(v) for v in FLOOR_POINTS_HZ)}]')
    print(f'      density_ug_per_sqrt_Hz: [{", ".join(f"{v * 1e6:.0f}" for v in floor)}]')
    return x, f_r, line


def slot_comb_levels(directory, others):
    """The slot-harmonic comb (the speed-locked orders above 100 of record 97) in each 12 kHz
    drive-end fault record (0.007-0.021 in, outer race at 6:00) against record 97: the summed power
    of its lines, each the largest within +-0.12 order of record 97's (the comb moves with the
    slip), in dB; a fault line within that reach counts too, so these are upper bounds."""
    comb = [order for order, _ in others if order > 100.0]

    def power(x, rpm):
        f_r = best_frequency(x, rpm / 60.0, range(9, 25), 0.3, steps=61)
        return sum(max(amplitude(x, o * f_r) for o in np.linspace(order - 0.12, order + 0.12, 49)) ** 2
                   for order in comb)

    x97, rpm97 = normal_record(directory)
    reference = power(x97[-60000:], rpm97)
    levels = {}
    for record, path in fault_records(directory).items():
        x, rpm = drive_end(path)
        levels[record] = 10.0 * np.log10(power(x[-60000:], rpm) / reference)
    return levels


def fault_records(directory):
    """The 12 kHz drive-end fault records of 0.007-0.021 in (outer race at 6:00): {record number: path}."""
    records = {}
    for path in sorted(directory.glob('12k_Drive_End_*.mat')):
        name = path.stem
        if not any(f'_{kind}{size}' in name for kind in ('IR', 'B', 'OR') for size in ('007', '014', '021')) or \
                ('_OR' in name and '@6' not in name):
            continue
        records[name.rsplit('_', 1)[1]] = path
    return records


def band_quantile_power(y):
    """The ROLLING_QUANTILE of y's power in ROLLING_BAND_HZ over blocks of ROLLING_BLOCK_S."""
    spectrum = np.fft.rfft(y - y.mean())
    f = np.fft.rfftfreq(len(y), 1.0 / FS)
    spectrum[(f < ROLLING_BAND_HZ[0]) | (f >= ROLLING_BAND_HZ[1])] = 0.0
    band = np.fft.irfft(spectrum, len(y))
    n = int(round(ROLLING_BLOCK_S * FS))
    blocks = (band[:len(band) // n * n].reshape(-1, n) ** 2).mean(axis=1)
    return np.quantile(blocks, ROLLING_QUANTILE)


@functools.lru_cache(maxsize=None)
def gaussian_quantile_share(samples):
    """band_quantile_power of `samples` of unit white noise over its band power
    2 (f_high - f_low) / FS (~0.6); computed once per length."""
    gaussian = np.random.default_rng(1).standard_normal(samples)
    return band_quantile_power(gaussian) / (2.0 * np.diff(ROLLING_BAND_HZ)[0] / FS)


def rolling_noise_levels(directory, modes, mount):
    """The fault records' rolling noise, ug/sqrt(Hz) of white acceleration at the ring: their random
    power in ROLLING_BAND_HZ (read between impacts, above) less record 97's, over the band's
    integral of |H_path T_m|^2."""
    f = np.arange(ROLLING_BAND_HZ[0], ROLLING_BAND_HZ[1], 0.5)
    h = (1.0 - sum(m['p'] for m in modes)) + sum(m['p'] * seismic(f, m['f'], m['zeta']) for m in modes)
    gain = np.sum(np.abs(h * seismic(f, mount['f'], mount['zeta'])) ** 2) * 0.5
    def random_power(x):  # the last 10 s at most
        x = x[-120000:]
        return band_quantile_power(x) / gaussian_quantile_share(len(x))

    x97, _ = normal_record(directory)
    normal = random_power(x97)
    levels = {}
    for record, path in fault_records(directory).items():
        x, _ = drive_end(path)
        extra = max(random_power(x) - normal, 0.0)
        levels[record] = np.sqrt(extra / gain) * 1e6
    return levels, np.sqrt(normal) * 1e3


def print_comparison(directory, csv_path, unit):
    real, rpm = normal_record(directory)
    sim = np.loadtxt(csv_path, delimiter=',', skiprows=1)[:, 1]
    sim = sim / G if unit == 'm_s2' else sim
    sim = sim[len(sim) // 2:]  # after the start-up transient
    rows = []
    for name, x in (('real, record 97', real), (f'simulated, {pathlib.Path(csv_path).name}', sim)):
        f_r, line = shaft_and_line(x, rpm)  # each record's own speed and line frequency
        rows.append((name, record_statistics(x, f_r, line)))
    keys = list(rows[0][1]['levels'])
    print('| record | RMS, g | power in lines | ' + ' | '.join(f'{k}, mg' for k in keys) +
          ' | floor at 500 Hz / 3 kHz, ug/sqrt(Hz) |')
    print('|---' * (4 + len(keys)) + '|')
    for name, s in rows:
        levels = ' | '.join(f"{s['levels'][k] * 1e3:.2f}" for k in keys)
        print(f"| {name} | {s['rms']:.4f} | {100 * s['line_share']:.0f} % | {levels} | "
              f"{s['floor'][0] * 1e6:.0f} / {s['floor'][1] * 1e6:.0f} |")


def mode_balance_db(x):
    """A record's power in BALANCE_LOW_HZ over that in BALANCE_HIGH_HZ, dB: the median over its
    1 s windows (modal_density)."""
    values = []
    for start in range(0, x.size - int(FS) + 1, int(FS)):
        f, p = modal_density(x[start:start + int(FS)])
        band = lambda b: p[(f >= b[0]) & (f < b[1])].sum()
        values.append(10.0 * np.log10(band(BALANCE_LOW_HZ) / band(BALANCE_HIGH_HZ)))
    return float(np.median(values))


def print_mode_balance(directory):
    """--mode-balance: mode_balance_db of each 12 kHz fault record of 0.007-0.021 in (all positions,
    BALANCE_UNSEEN left out), by assembly (the four loads of one fault), and its percentiles."""
    by_assembly = {}
    for path in sorted(directory.glob('12k_Drive_End_*.mat')):
        assembly = path.stem.split('_')[3]  # 12k_Drive_End_<fault><size>[@<position>]_<hp>_<record>
        if not re.fullmatch(r'(IR|B|OR)(007|014|021)(@\d+)?', assembly) or assembly in BALANCE_UNSEEN:
            continue
        x, _ = drive_end(path)
        by_assembly.setdefault(assembly, []).append(mode_balance_db(x))
    values = [v for v in by_assembly.values() for v in v]
    print(f"# The path's {BALANCE_LOW_HZ[0]:.0f}-{BALANCE_LOW_HZ[1]:.0f} Hz power over its "
          f"{BALANCE_HIGH_HZ[0]:.0f}-{BALANCE_HIGH_HZ[1]:.0f} Hz power, dB, by assembly (0-3 hp):")
    for assembly, v in by_assembly.items():
        print(f"#   {assembly}: {', '.join(f'{x:+.0f}' for x in v)}")
    p10, p50, p90 = np.percentile(values, [10, 50, 90])
    print(f'#   {len(values)} records: 10th / 50th / 90th percentile {p10:+.1f} / {p50:+.1f} / {p90:+.1f} dB')


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('cwru_dir', type=pathlib.Path, help='directory of the CWRU .mat files')
    parser.add_argument('--compare', metavar='CSV', help='a simulated --sensor-csv to compare with record 97')
    parser.add_argument('--compare-unit', choices=('m_s2', 'g'), default='m_s2')
    parser.add_argument('--slot-comb', action='store_true',
                        help='also measure the slot-harmonic comb in the 12 kHz fault records against record 97')
    parser.add_argument('--rolling-noise', action='store_true',
                        help='also measure the 12 kHz fault records\' rolling noise (white at the ring) beyond record 97\'s')
    parser.add_argument('--mode-spread', action='store_true',
                        help="also measure how far the path's peaks move from record to record")
    parser.add_argument('--mode-balance', action='store_true',
                        help="also measure the path's low modes against its 2.9 kHz mode, assembly by assembly")
    args = parser.parse_args()
    if not (args.cwru_dir / NORMAL).is_file():
        sys.exit(f'{args.cwru_dir}: no {NORMAL} (the CWRU normal baseline, record 97)')
    if args.compare:
        print_comparison(args.cwru_dir, args.compare, args.compare_unit)
    else:
        print_installation(args.cwru_dir, args.slot_comb, args.rolling_noise, args.mode_spread)
    if args.mode_balance:
        print_mode_balance(args.cwru_dir)


if __name__ == '__main__':
    main()
