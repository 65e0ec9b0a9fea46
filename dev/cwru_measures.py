"""Measures of an acceleration record that compare real and simulated CWRU drive-end data
(dev/cwru_rig_compare.py) and serve as a classifier's features
(dev/cwru_classifier_check.py): the power spectral density, the shares of the power in
frequency bands and in discrete lines, and envelope-spectrum levels at given frequencies.
Pure functions of numpy arrays (SI units: m/s^2, Hz); tested in
test/python/test_cwru_measures.py."""
import numpy as np

# The bands of issue 30's comparison, Hz: below the rotor's radial mode and the fault lines'
# low harmonics, then octaves up to the 12 kHz records' Nyquist frequency.
BANDS_HZ = ((0.0, 500.0), (500.0, 1000.0), (1000.0, 2000.0), (2000.0, 4000.0), (4000.0, 6000.0))
# Discrete lines: PSD bins of a 1 s Hann Welch estimate standing more than LINE_THRESHOLD_DB
# over the running median of the PSD across LINE_MEDIAN_HZ. 10 dB: a bin of a Gaussian floor
# exceeds its median by 10 dB with probability exp(-10 ln 2) = 1e-3 (one segment, chi^2 with
# 2 degrees of freedom), so the floor contributes almost nothing; 51 Hz spans more than the
# line spacing of the rig's families (30 Hz shaft orders) so the median is the floor's.
LINE_THRESHOLD_DB = 10.0
LINE_MEDIAN_HZ = 51.0
SEGMENT_S = 1.0  # Welch segment: 1 Hz resolution, the analyser's with window_s = 1


def windows(signal, samples):
    """Non-overlapping windows of `samples`, the last one ending at the signal's end (a record's
    start may hold a transient; its end is what the analysis of a record reads)."""
    count = len(signal) // samples
    start = len(signal) - count * samples
    return [signal[start + i * samples:start + (i + 1) * samples] for i in range(count)]


def psd(signal, sample_rate_hz, segment_s=SEGMENT_S):
    """One-sided PSD ((m/s^2)^2/Hz) of a record: Welch, Hann segments of segment_s (the whole
    record when shorter), 50 % overlap, mean removed per segment. Returns (frequencies_hz, psd)."""
    from scipy.signal import welch
    x = np.asarray(signal, dtype=float)
    n = min(x.size, int(round(segment_s * sample_rate_hz)))
    return welch(x, fs=sample_rate_hz, window='hann', nperseg=n, noverlap=n // 2, detrend='constant')


def band_shares(frequencies_hz, density, bands_hz=BANDS_HZ):
    """Share (0-1) of the power of a PSD in each band [low, high) (the last band includes the
    Nyquist bin); the shares of bands that tile 0..Nyquist sum to 1."""
    f, p = np.asarray(frequencies_hz), np.asarray(density)
    total = p.sum()
    shares = []
    for i, (low, high) in enumerate(bands_hz):
        inside = (f >= low) & ((f < high) if i < len(bands_hz) - 1 else (f <= high))
        shares.append(float(p[inside].sum() / total) if total > 0 else 0.0)
    return shares


def line_floor(frequencies_hz, density, median_hz=LINE_MEDIAN_HZ):
    """The PSD's running median across median_hz (an odd number of bins): the floor under lines."""
    from scipy.ndimage import median_filter
    resolution = frequencies_hz[1] - frequencies_hz[0]
    bins = max(3, int(round(median_hz / resolution)) | 1)
    return median_filter(np.asarray(density, dtype=float), size=bins, mode='nearest')


def line_share(frequencies_hz, density, threshold_db=LINE_THRESHOLD_DB, median_hz=LINE_MEDIAN_HZ):
    """Share (0-1) of a PSD's power in discrete lines: the excess over the running-median floor
    of the bins more than threshold_db above it, over the total power (the DC bin left out:
    the mean is removed)."""
    p = np.asarray(density, dtype=float)[1:]
    floor = line_floor(frequencies_hz, density, median_hz)[1:]
    above = p > floor * 10.0 ** (threshold_db / 10.0)
    total = p.sum()
    return float((p[above] - floor[above]).sum() / total) if total > 0 else 0.0


def band_passed(signal, sample_rate_hz, band_hz):
    """The signal band-passed to band_hz (Butterworth order 4, zero phase; the upper edge held
    below 0.98 x Nyquist)."""
    from scipy.signal import butter, sosfiltfilt
    nyquist = sample_rate_hz / 2.0
    sos = butter(4, [band_hz[0] / nyquist, min(band_hz[1], 0.98 * nyquist) / nyquist], btype='bandpass',
                 output='sos')
    return sosfiltfilt(sos, np.asarray(signal, dtype=float))


def squared_envelope(signal, sample_rate_hz, band_hz):
    """The squared envelope of the signal band-passed to band_hz, its mean removed."""
    from scipy.signal import hilbert
    envelope = np.abs(hilbert(band_passed(signal, sample_rate_hz, band_hz))) ** 2
    return envelope - envelope.mean()


def envelope_spectrum(signal, sample_rate_hz, band_hz):
    """Squared-envelope spectrum of the signal band-passed to band_hz (band_passed):
    (frequencies_hz, amplitude), mean removed, normalised by the sample count."""
    envelope = squared_envelope(signal, sample_rate_hz, band_hz)
    amplitude = np.abs(np.fft.rfft(envelope)) / envelope.size
    return np.fft.rfftfreq(envelope.size, 1.0 / sample_rate_hz), amplitude


LINE_TOLERANCE = 0.02  # a fault line's relative search width: slip and speed error (1-2 %)


def line_level_db(frequencies_hz, amplitude, line_hz, tolerance=LINE_TOLERANCE, floor_hz=(5.0, 500.0)):
    """Level (dB) of the highest envelope-spectrum bin within +-tolerance (relative) of line_hz
    over the median of the spectrum in floor_hz: how far a fault line stands out of the floor,
    whatever the record's unit and level. The tolerance covers slip and speed error (1-2 %)."""
    return line_levels_db(frequencies_hz, amplitude, [line_hz], [tolerance], floor_hz)[0]


def line_levels_db(frequencies_hz, amplitude, lines_hz, tolerances, floor_hz=(5.0, 500.0)):
    """line_level_db of several lines of one spectrum, each with its own relative tolerance; the
    floor's median taken once."""
    f, a = np.asarray(frequencies_hz), np.asarray(amplitude)
    floor = np.median(a[(f >= floor_hz[0]) & (f <= floor_hz[1])])
    levels = []
    for line_hz, tolerance in zip(lines_hz, tolerances):
        near = np.abs(f - line_hz) <= tolerance * line_hz
        levels.append(float(20.0 * np.log10(a[near].max() / floor)) if near.any() and floor > 0.0 else 0.0)
    return levels


# The band of the per-pass strength: the path's modes that the impacts ring (2.5-3.7 kHz) and
# the sensor's mount, clear of the shaft lines and the 4.0-4.4 kHz slot comb's upper part.
PASS_BAND_HZ = (2000.0, 4500.0)


def pass_strengths(signal, sample_rate_hz, fault_hz, band_hz=PASS_BAND_HZ):
    """Strength of a fault's impacts pass by pass: the RMS of the signal band-passed to band_hz
    (Butterworth order 4, zero phase) in each whole period 1 / fault_hz from the record's start.
    Returns (strengths, times_s), times_s each period's middle."""
    y = band_passed(signal, sample_rate_hz, band_hz)
    period = sample_rate_hz / fault_hz
    count = int(y.size / period)
    edges = (np.arange(count + 1) * period).astype(int)
    strengths = np.array([np.sqrt(np.mean(y[a:b] ** 2)) for a, b in zip(edges[:-1], edges[1:])])
    return strengths, (edges[:-1] + edges[1:]) / (2.0 * sample_rate_hz)


def pass_scatter(signal, sample_rate_hz, fault_hz, shaft_hz, band_hz=PASS_BAND_HZ):
    """How unequal a fault's impacts are from pass to pass: (coefficient of variation of
    pass_strengths, depth of their shaft-rate modulation). The depth m is that of
    s = s0 (1 + m cos(2 pi f_r t + phi)) fitted by the Fourier sum at f_r:
    m = 2 |sum s exp(-2 pi i f_r t)| / sum s (a modulation at the shaft rate comes from a load
    that varies once per turn: unbalance, runout, misalignment)."""
    s, t = pass_strengths(signal, sample_rate_hz, fault_hz, band_hz)
    if s.size < 2 or s.mean() <= 0.0:
        return float('nan'), float('nan')
    depth = 2.0 * abs(np.sum(s * np.exp(-2j * np.pi * shaft_hz * t))) / s.sum()
    return float(s.std() / s.mean()), float(depth)


def fault_frequency(signal, sample_rate_hz, nominal_hz, tolerance=LINE_TOLERANCE, band_hz=PASS_BAND_HZ):
    """The fault's actual impact rate near nominal_hz (slip moves it 1-2 %): the highest bin of the
    squared envelope's spectrum within +-tolerance of it, zero-padded to a sixteenth of a bin."""
    envelope = squared_envelope(signal, sample_rate_hz, band_hz)
    n = 16 * envelope.size
    spectrum = np.abs(np.fft.rfft(envelope, n))
    f = np.fft.rfftfreq(n, 1.0 / sample_rate_hz)
    near = np.abs(f - nominal_hz) <= tolerance * nominal_hz
    return float(f[near][np.argmax(spectrum[near])])


def ball_scatter(signal, sample_rate_hz, fault_hz, balls, band_hz=PASS_BAND_HZ, shuffles=20, seed=0):
    """How unequally the balls strike a standing (outer-race) fault: the balls pass it in their
    order, so pass k is ball k mod `balls`. Returns (coefficient of variation of the balls' mean
    pass strengths, the same with the passes shuffled: what the pass-to-pass scatter alone
    leaves in means of as many passes). fault_hz must be the actual rate (fault_frequency), or
    the passes slide across the periods."""
    s, _ = pass_strengths(signal, sample_rate_hz, fault_hz, band_hz)
    s = s[:(s.size // balls) * balls]
    if s.size < 2 * balls or s.mean() <= 0.0:
        return float('nan'), float('nan')

    def spread(strengths):
        means = strengths.reshape(-1, balls).mean(axis=0)
        return float(means.std() / means.mean())

    rng = np.random.default_rng(seed)
    return spread(s), float(np.mean([spread(rng.permutation(s)) for _ in range(shuffles)]))


def spin_axis_wander_deg(snr_drop_db, half_width_deg):
    """The balls' spin-axis wander (standard deviation of a ball spall's latitude from the
    rolling track, deg) that lowers a ball spall's 2 x BSF envelope line by snr_drop_db: a
    spall of half width h (deg of the ball's great circle) is struck the share
    p = erf(h / (sigma sqrt 2)) of the time (docs/model.md 9.5), and the line's amplitude goes
    with p against a floor that is the machine's, so the drop is -20 log10 p. 0 for no drop."""
    from scipy.special import erfinv
    share = 10.0 ** (-snr_drop_db / 20.0)
    if share >= 1.0:
        return 0.0
    return float(half_width_deg / (np.sqrt(2.0) * erfinv(share)))
