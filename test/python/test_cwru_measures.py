"""dev/cwru_measures.py, the measures that compare real and simulated CWRU records: band
shares and the share of the power in discrete lines against synthetic signals of known
power, and the envelope-spectrum level of an impact train at its rate."""
import math
import sys

import numpy as np

from conftest import SOURCE

sys.path.insert(0, str(SOURCE / 'dev'))
import cwru_measures  # noqa: E402

FS = 12000.0


def white(seconds, power, seed=1):
    return math.sqrt(power) * np.random.default_rng(seed).standard_normal(int(seconds * FS))


def sine(seconds, frequency_hz, power):
    t = np.arange(int(seconds * FS)) / FS
    return math.sqrt(2.0 * power) * np.sin(2.0 * math.pi * frequency_hz * t + 0.3)


def test_band_shares_split_the_power_of_two_tones_and_sum_to_one():
    x = sine(4.0, 250.0, 1.0) + sine(4.0, 3000.0, 3.0)
    shares = cwru_measures.band_shares(*cwru_measures.psd(x, FS))
    # A Hann window's leakage beyond its main lobe is < 1e-5 of the tone's power.
    assert np.allclose(shares, [0.25, 0.0, 0.0, 0.75, 0.0], atol=1e-3)
    noise_shares = cwru_measures.band_shares(*cwru_measures.psd(white(4.0, 1.0), FS))
    assert math.isclose(sum(noise_shares), 1.0, rel_tol=1e-12)
    # White noise: each band's share is its width over 6 kHz (4 s: 7 segments, a few % scatter).
    widths = [(hi - lo) / 6000.0 for lo, hi in cwru_measures.BANDS_HZ]
    assert np.allclose(noise_shares, widths, rtol=0.05)


def test_line_share_is_the_tones_power_over_the_total():
    # Tones between bins (the Hann window's worst case), 2 of power 1 and 0.5 over white noise
    # of power 1.5: half the power is in lines. The floor under the tones is subtracted; the
    # estimate of the noise power over 19 segments scatters by ~0.3 %, and the tones' skirts
    # below the 10 dB threshold hold < 0.1 % of their power: 1 % tolerance.
    x = sine(10.0, 1234.5, 1.0) + sine(10.0, 3210.5, 0.5) + white(10.0, 1.5)
    share = cwru_measures.line_share(*cwru_measures.psd(x, FS))
    assert abs(share - 0.5) < 0.01


def test_noise_alone_has_no_lines_and_impacts_are_lines():
    assert cwru_measures.line_share(*cwru_measures.psd(white(10.0, 1.0), FS)) < 0.002
    # A periodic impact train is a comb of lines: nearly all its power is in them.
    n = int(4.0 * FS)
    impacts = np.zeros(n)
    impacts[::120] = 1.0  # 100 Hz
    t = np.arange(240) / FS
    ring = np.exp(-0.05 * 2 * math.pi * 3000.0 * t) * np.sin(2 * math.pi * 3000.0 * t)
    train = np.convolve(impacts, ring)[:n]
    assert cwru_measures.line_share(*cwru_measures.psd(train + 0.001 * white(4.0, 1.0), FS)) > 0.95


def test_envelope_line_level_stands_out_at_the_impact_rate_only():
    n = int(2.0 * FS)
    impacts = np.zeros(n)
    impacts[(np.arange(0.0, 2.0, 1.0 / 107.3) * FS).astype(int)] = 1.0
    t = np.arange(240) / FS
    ring = np.exp(-0.05 * 2 * math.pi * 3000.0 * t) * np.sin(2 * math.pi * 3000.0 * t)
    x = np.convolve(impacts, ring)[:n] + 0.05 * white(2.0, 1.0)
    f, a = cwru_measures.envelope_spectrum(x, FS, (2000.0, 4000.0))
    assert cwru_measures.line_level_db(f, a, 107.3) > 20.0
    # Midway between its 1st and 2nd harmonics there is only the floor.
    assert cwru_measures.line_level_db(f, a, 161.0) < 10.0


def test_pass_scatter_reads_a_shaft_rate_modulation_of_the_impacts():
    # Impacts at 107.3 Hz whose strengths follow 1 + m cos(2 pi f_r t), f_r = 29.93 Hz, m = 0.6:
    # the pass strengths' coefficient of variation is m / sqrt(2) (the mean of cos^2 is 1/2; the
    # shaft's phase at the passes is spread evenly, 107.3 / 29.93 is not a ratio of small
    # integers) and the depth read at f_r is m. Each ringing (12 % of a period long, 3 % damped)
    # stays in its own period; the band-pass filter's own ringing and the noise: 0.03.
    m, shaft_hz, fault_hz = 0.6, 29.93, 107.3
    n = int(10.0 * FS)
    times = np.arange(0.3 / fault_hz, 10.0 - 1.0 / fault_hz, 1.0 / fault_hz)
    impacts = np.zeros(n)
    impacts[(times * FS).astype(int)] = 1.0 + m * np.cos(2.0 * math.pi * shaft_hz * times)
    t = np.arange(int(0.3 * FS / fault_hz)) / FS
    ring = np.exp(-0.03 * 2 * math.pi * 3000.0 * t) * np.sin(2 * math.pi * 3000.0 * t)
    x = np.convolve(impacts, ring)[:n] + 0.001 * white(10.0, 1.0)
    cv, depth = cwru_measures.pass_scatter(x, FS, fault_hz, shaft_hz)
    assert abs(depth - m) < 0.03
    assert abs(cv - m / math.sqrt(2.0)) < 0.03
    # Equal impacts: no modulation, and a scatter of 0.03 from the whole samples (a period is
    # 111.8 samples, the impacts fall on whole samples) and the filter's ringing across periods.
    impacts[impacts > 0] = 1.0
    cv, depth = cwru_measures.pass_scatter(np.convolve(impacts, ring)[:n], FS, fault_hz, shaft_hz)
    assert cv < 0.04 and depth < 0.01


def test_ball_scatter_reads_each_balls_own_strength_and_the_fault_frequency_its_rate():
    # Nine balls striking a standing fault at 104.9 Hz (2 % below the nominal 107.0: slip), ball b
    # with strength g_b: the means of the passes of each ball are the g_b, whose coefficient of
    # variation is written out here. Each ringing (3 % damped, 30 % of a period long) stays in its
    # own period, 0.3 of a period from its start; whole samples and the filter's ringing across
    # periods: 0.01. Shuffled, the passes of a ball are any nine-th of them: their means' spread
    # is that of g over sqrt(passes per ball) (~1 / 10 of it here), far below.
    fault_hz, nominal_hz, balls = 104.9, 107.0, 9
    n = int(10.0 * FS)
    times = np.arange(0.3 / fault_hz, 10.0 - 1.0 / fault_hz, 1.0 / fault_hz)
    gains = 1.0 + 0.3 * np.sin(np.arange(balls) * 2.1)
    impacts = np.zeros(n)
    impacts[np.rint(times * FS).astype(int)] = gains[np.arange(times.size) % balls]
    t = np.arange(int(0.3 * FS / fault_hz)) / FS
    ring = np.exp(-0.03 * 2 * math.pi * 3000.0 * t) * np.sin(2 * math.pi * 3000.0 * t)
    x = np.convolve(impacts, ring)[:n] + 0.001 * white(10.0, 1.0)
    found = cwru_measures.fault_frequency(x, FS, nominal_hz)
    assert abs(found - fault_hz) < 0.01 * fault_hz
    cv, shuffled = cwru_measures.ball_scatter(x, FS, fault_hz, balls)
    assert abs(cv - gains.std() / gains.mean()) < 0.01
    assert shuffled < 0.3 * cv
    # Equal balls: no spread but the samples' rounding.
    impacts[impacts > 0] = 1.0
    cv, _ = cwru_measures.ball_scatter(np.convolve(impacts, ring)[:n], FS, fault_hz, balls)
    assert cv < 0.01


def test_spin_axis_wander_that_halves_a_ball_line_is_the_half_width_over_the_normal_quartile():
    # A line lowered by 20 log10 2 = 6.02 dB: the spall is struck half the time, so its latitude
    # lies within the half width h half the time: h is the normal's quartile, 0.67449 sigma
    # (sigma = 1.482602 h, the median absolute deviation's constant).
    assert math.isclose(cwru_measures.spin_axis_wander_deg(20.0 * math.log10(2.0), 2.0), 2.0 * 1.482602,
                        rel_tol=1e-6)
    # 20 dB: struck a tenth of the time, erf(x) = 0.1 at x = 0.088856 (tables).
    assert math.isclose(cwru_measures.spin_axis_wander_deg(20.0, 1.0), 1.0 / (math.sqrt(2.0) * 0.0888559),
                        rel_tol=1e-5)
    # No drop: always struck, no wander.
    assert cwru_measures.spin_axis_wander_deg(0.0, 2.0) == 0.0
    assert cwru_measures.spin_axis_wander_deg(-3.0, 2.0) == 0.0


def test_windows_end_at_the_signal_s_end_and_do_not_overlap():
    x = np.arange(25)
    cut = cwru_measures.windows(x, 10)
    # 25 samples hold two whole windows of 10; the 5 left over are the first ones, dropped.
    assert [list(w) for w in cut] == [list(range(5, 15)), list(range(15, 25))]
    assert cwru_measures.windows(x, 30) == []
