#pragma once
// FFT helpers for vibration analysis (Eigen's kissfft backend, header-only): amplitude
// spectrum, band-pass by FFT masking, Hilbert envelope, velocity by frequency-domain
// integration, and a peak search with a signal-to-noise ratio.
//
// Lengths: any length works; kissfft is fast when the length has only small prime
// factors (see fft_friendly_length), slow (O(n p)) for a large prime factor p.
#include <cstddef>
#include <vector>

namespace bearing_sim {

// A single-sided amplitude spectrum: bin k at k * resolution_hz, k = 0 .. n/2.
struct Spectrum {
  double resolution_hz = 0.0;
  std::vector<double> amplitude;
  double frequency_hz(std::size_t bin) const { return static_cast<double>(bin) * resolution_hz; }
};

// Largest m <= n of the form 2^a 3^b 5^c (m >= 1 for n >= 1); analyses keep the last m
// samples so that no FFT meets a large prime factor (at most a few percent are dropped).
std::size_t fft_friendly_length(std::size_t n);

// Mean removed, Hann window, scaled by the window's coherent gain: a sine of amplitude A
// at a bin centre reads A there (up to 1.42 dB less between bins).
Spectrum amplitude_spectrum(const std::vector<double>& x, double sample_rate_hz);

// Zero-phase band-pass by FFT masking: the bins outside [low_hz, high_hz] are zeroed.
std::vector<double> band_pass(const std::vector<double>& x, double sample_rate_hz, double low_hz, double high_hz);

// |analytic signal| of x (the Hilbert envelope), mean of x removed.
std::vector<double> hilbert_envelope(const std::vector<double>& x);

// Envelope of x band-passed to [low_hz, high_hz], in one FFT pair (band mask and
// analytic signal together): the demodulation step of envelope analysis.
std::vector<double> band_envelope(const std::vector<double>& x, double sample_rate_hz, double low_hz, double high_hz);

// Amplitude spectrum (as amplitude_spectrum) of band_envelope: the envelope spectrum.
Spectrum envelope_spectrum(const std::vector<double>& x, double sample_rate_hz, double low_hz, double high_hz);

// Cepstral pre-whitening (Sawalhi & Randall; Borghesani et al., MSSP 36, 2013): every bin of
// the spectrum set to unit magnitude, its phase kept, so that the discrete lines (shaft
// orders, the electrical line family, gear meshes) and the transmission path's colouring
// are flattened while impacts, which are broadband and phase-coherent, stay impulsive. A
// bin below floor_per_bin keeps its magnitude relative to the floor (x_k / floor): a
// sensor's noise floor, so that the rounding noise of a noise-free simulation is not
// raised to the level of its lines. Mean removed; the result has the length of x.
std::vector<double> prewhiten(const std::vector<double>& x, double floor_per_bin = 0.0,
                              double* share_below_floor = nullptr);  // of the bins
// The DFT magnitude one bin of white noise of this one-sided density (units/sqrt(Hz)) has
// in an n-sample transform at sample_rate_hz (its RMS over the bins): sqrt(n fs / 2) d.
double white_noise_bin_magnitude(double density_per_sqrt_hz, std::size_t n, double sample_rate_hz);
// Envelope spectrum averaged over segments (Welch): the band envelope of the whole x,
// then cut into segments of segment_samples overlapping by half, each mean-removed,
// Hann-windowed and transformed; the amplitude is the RMS over the segments of the
// amplitude-corrected bins (a line of amplitude A reads A). Averaging keeps the lines and
// narrows the spread of the noise bins (K segments: a chi-square of about 2K degrees of
// freedom per bin instead of 2), which is what makes weak lines of a long record
// significant; short segments follow a wandering speed. segments_out: K; envelope_mean_out:
// the mean of the whole envelope.
Spectrum averaged_envelope_spectrum(const std::vector<double>& x, double sample_rate_hz, double low_hz, double high_hz,
                                    std::size_t segment_samples, std::size_t* segments_out = nullptr,
                                    double* envelope_mean_out = nullptr);
// The number of independent spectra that K Hann segments overlapping by half are worth
// (Welch 1967: the overlap correlates neighbours by 0.167 in power): K / (1 + 2 0.167^2)
// for K > 1, else K.
double equivalent_averages(std::size_t segments);
// The threshold over the median of the bins (dB, amplitude) that an average of
// `averages` power spectra of Gaussian noise exceeds with the same per-bin probability as
// a single spectrum (Rayleigh bins) exceeds single_threshold_db: the bins' power is then
// Gamma(K, 1/K) distributed (K = floor(averages)); a threshold set for one spectrum keeps
// its false-alarm rate when the spectrum is averaged.
double averaged_threshold_db(double single_threshold_db, double averages);

// Velocity (m/s) from acceleration (m/s^2) by dividing each bin by j omega, keeping only
// [low_hz, high_hz]; no window, so the ends of the record carry some leakage.
std::vector<double> integrate_to_velocity(const std::vector<double>& accel, double sample_rate_hz, double low_hz,
                                          double high_hz);

// RMS velocity (m/s) in [low_hz, high_hz] from the Hann-windowed acceleration spectrum by
// Parseval, sum over the band of |A_k|^2 / omega_k^2 with the window's energy correction.
// The window keeps a strong tone outside the band from leaking in (which, divided by a
// small omega, would dominate a low-frequency band).
double band_velocity_rms(const std::vector<double>& accel, double sample_rate_hz, double low_hz, double high_hz);

// Fast kurtogram (after Antoni 2007, "Fast computation of the kurtogram for the detection of
// transient faults", MSSP 21:108-124), simplified: the 1/3-binary tree of bands tiling
// [0, fs/2] (level k: 2^k bands; level k + log2(3) - 1: 3 x 2^(k-1) bands, i.e. 1, 2, 3, 4,
// 6, 8, 12, ... bands), each band's complex envelope taken by FFT masking (the band's bins
// of one forward FFT of the Tukey-tapered window, moved to baseband, zero-padded x2 and
// inverse-transformed: an ideal band-pass instead of Antoni's quasi-analytic FIR filter
// bank; the tapered ends left out), and its spectral kurtosis
// SK = <|c|^4> / <|c|^2>^2 - 2 (0 for Gaussian noise, large for an impulse train).
struct KurtogramBand {
  int bands_in_level = 1;  // 1, 2, 3, 4, 6, 8, 12, ...: width = (fs/2) / bands_in_level
  double low_hz = 0.0, high_hz = 0.0;
  double kurtosis = 0.0;             // spectral kurtosis of the band's complex envelope
  double independent_samples = 0.0;  // as in BandKurtosis below
};
struct Kurtogram {
  std::vector<KurtogramBand> bands;  // every band evaluated, level by level
  KurtogramBand best;                // the largest kurtosis (the widest band on a tie)
};
// Bands narrower than min_width_hz (at least the envelope lines one wants to see) or with a
// low edge below min_low_hz are skipped; levels up to bands_in_level <= max_bands.
// floor_density > 0 (units/sqrt(Hz)): each band's kurtosis as it would be with white noise
// of that density added (a sensor's floor), SK (P / (P + P_floor))^2 for the band power P:
// a noise-free signal's faint bursts are not the most impulsive band.
// Throws InvalidInputError when no band qualifies.
Kurtogram fast_kurtogram(const std::vector<double>& x, double sample_rate_hz, double min_width_hz,
                         double min_low_hz = 0.0, int max_bands = 64, double floor_density = 0.0);

// Spectral kurtosis of one band [low_hz, high_hz), computed as a kurtogram band is (the
// tapered window, the band's complex envelope, its tapered ends left out). For Gaussian
// noise SK is 0 with a standard deviation of about 2 / sqrt(independent_samples) (the
// band's bins, i.e. width x window duration, less the tapered ends); a stationary line
// series gives SK < 0 (a pure tone -1), a train of short impacts SK > 0.
struct BandKurtosis {
  bool valid = false;  // the band holds enough bins (> 8)
  double kurtosis = 0.0;
  double independent_samples = 0.0;
};
BandKurtosis band_spectral_kurtosis(const std::vector<double>& x, double sample_rate_hz, double low_hz, double high_hz,
                                    double floor_density = 0.0);  // as for fast_kurtogram

// Peak search around an expected frequency.
struct PeakSearchOptions {
  double tolerance_rel = 0.01;  // search expected * (1 +- tolerance_rel) ...
  // ... but at least +- one bin: the nearest bin of a line is within half a bin of it, and a
  // wider window near a low frequency (FTF) would catch unrelated lines.
  int tolerance_min_bins = 1;
  int noise_half_width_bins = 30;  // noise floor from the bins within +- this of the peak ...
  int noise_exclude_bins = 3;      // ... leaving out the peak's own Hann main lobe (+- this)
};

struct SpectralPeak {
  bool searched = false;       // false: the expected frequency is not inside the spectrum
  bool local_maximum = false;  // the largest bin is a peak of the spectrum, not the flank
                               // of a line outside the search range
  double expected_hz = 0.0;
  double frequency_hz = 0.0;  // of the largest bin, refined by Gaussian interpolation
  double amplitude = 0.0;     // of the largest bin
  double noise_floor = 0.0;   // MEDIAN of the neighbouring bins (robust to other lines)
  double snr_db = 0.0;        // 20 lg(amplitude / max(noise_floor, absolute_floor))
  // The chance that a search window this wide holds a local maximum at least this high
  // where no line of the searched series lies (line_chance; 1 until computed).
  double chance = 1.0;
};

// absolute_floor: the SNR is taken against at least this (e.g. the sensor's noise floor
// per bin), so that numerically tiny lines of a near-perfect signal do not count.
SpectralPeak find_peak(const Spectrum& spectrum, double expected_hz, const PeakSearchOptions& options = {},
                       double absolute_floor = 0.0);
// The chance that a window of the peak's search width (+-window_half_hz) holds, by chance,
// a local maximum at least as high as the peak: the density of such maxima per Hz in the
// neighbourhood (+-neighbourhood_rel of the expected frequency, at least +-noise_half_width
// bins), leaving out the peak's own window and the windows of `own_lines_hz` (the other
// lines of the hypothesis being tested), counted with half a maximum added (so that an
// empty neighbourhood does not give certainty), as a Poisson rate: 1 - exp(-rate width).
// A real machine's envelope spectrum is dense with lines (shaft orders, the supply's
// family, other components): there a +-1 % window finds "a line" by chance, and an SNR
// over the median floor says nothing about that.
double line_chance(const Spectrum& spectrum, const SpectralPeak& peak, double window_half_hz,
                   const std::vector<double>& own_lines_hz, double neighbourhood_rel, const PeakSearchOptions& options);

}  // namespace bearing_sim
