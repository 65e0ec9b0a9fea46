#include "bearing_sim/core/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numeric>
#include <string>

#include <unsupported/Eigen/FFT>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {
namespace {
using Complex = std::complex<double>;

void check_signal(const std::vector<double>& x, double sample_rate_hz, const char* what) {
  if (x.size() < 4) throw InvalidInputError(std::string(what) + ": at least 4 samples are needed");
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz))
    throw InvalidInputError(std::string(what) + ": the sample rate must be a positive number of Hz");
  for (double v : x)
    if (!std::isfinite(v)) throw InvalidInputError(std::string(what) + ": the signal has a non-finite sample");
}

void check_band(double low_hz, double high_hz, const char* what) {
  if (!(low_hz >= 0.0) || !(high_hz > low_hz) || !std::isfinite(high_hz))
    throw InvalidInputError(std::string(what) + ": the band must satisfy 0 <= low < high");
}

double mean_of(const std::vector<double>& x) {
  long double s = 0.0L;
  for (double v : x) s += v;
  return static_cast<double>(s / static_cast<long double>(x.size()));
}

// Full complex spectrum of x with its mean removed.
std::vector<Complex> forward(const std::vector<double>& x) {
  const double m = mean_of(x);
  std::vector<double> centred(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) centred[i] = x[i] - m;
  std::vector<Complex> spectrum;
  Eigen::FFT<double> fft;
  fft.fwd(spectrum, centred);
  return spectrum;
}

bool in_band(double f, double low_hz, double high_hz) { return f >= low_hz && f <= high_hz; }

// Analytic signal of x restricted to a band: 2 X_k for the positive frequencies in the
// band, 0 elsewhere (the DC and Nyquist bins are never in a band that excludes them).
std::vector<Complex> analytic_band(const std::vector<double>& x, double fs, double low_hz, double high_hz) {
  std::vector<Complex> spectrum = forward(x);
  const std::size_t n = spectrum.size();
  const double df = fs / static_cast<double>(n);
  for (std::size_t k = 0; k < n; ++k) {
    const bool positive = k >= 1 && 2 * k < n;
    const bool keep = positive && in_band(k * df, low_hz, high_hz);
    spectrum[k] = keep ? 2.0 * spectrum[k] : Complex(0.0, 0.0);
  }
  std::vector<Complex> z;
  Eigen::FFT<double> fft;
  fft.inv(z, spectrum);  // scaled by 1/n
  return z;
}

std::vector<double> hann(std::size_t n) {
  std::vector<double> w(n);
  for (std::size_t i = 0; i < n; ++i) w[i] = 0.5 - 0.5 * std::cos(2.0 * kPi * i / static_cast<double>(n));
  return w;  // periodic form: exact coherent gain 1/2 and energy 3/8
}
}  // namespace

std::size_t fft_friendly_length(std::size_t n) {
  if (n == 0) return 0;
  std::size_t best = 1;
  for (std::size_t a = 1; a <= n; a *= 2)
    for (std::size_t b = a; b <= n; b *= 3)
      for (std::size_t c = b; c <= n; c *= 5) best = std::max(best, c);
  return best;
}

Spectrum amplitude_spectrum(const std::vector<double>& x, double sample_rate_hz) {
  check_signal(x, sample_rate_hz, "amplitude spectrum");
  const std::size_t n = x.size();
  const double m = mean_of(x);
  const std::vector<double> w = hann(n);
  std::vector<double> windowed(n);
  for (std::size_t i = 0; i < n; ++i) windowed[i] = (x[i] - m) * w[i];
  std::vector<Complex> spectrum;
  Eigen::FFT<double> fft;
  fft.fwd(spectrum, windowed);
  Spectrum s;
  s.resolution_hz = sample_rate_hz / static_cast<double>(n);
  s.amplitude.resize(n / 2 + 1);
  // Single-sided, divided by the coherent gain sum(w) = n/2.
  for (std::size_t k = 0; k <= n / 2; ++k) {
    const double factor = (k == 0 || 2 * k == n) ? 1.0 : 2.0;
    s.amplitude[k] = factor * std::abs(spectrum[k]) / (0.5 * static_cast<double>(n));
  }
  return s;
}

std::vector<double> band_pass(const std::vector<double>& x, double sample_rate_hz, double low_hz, double high_hz) {
  check_signal(x, sample_rate_hz, "band-pass");
  check_band(low_hz, high_hz, "band-pass");
  const std::vector<Complex> z = analytic_band(x, sample_rate_hz, low_hz, high_hz);
  std::vector<double> y(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) y[i] = z[i].real();  // Re of the analytic signal
  return y;
}

std::vector<double> hilbert_envelope(const std::vector<double>& x) {
  // Every positive frequency: a band from 0 to beyond Nyquist at a unit sample rate.
  check_signal(x, 1.0, "Hilbert envelope");
  const std::vector<Complex> z = analytic_band(x, 1.0, 0.0, 1.0);
  std::vector<double> e(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) e[i] = std::abs(z[i]);
  return e;
}

std::vector<double> band_envelope(const std::vector<double>& x, double sample_rate_hz, double low_hz, double high_hz) {
  check_signal(x, sample_rate_hz, "band envelope");
  check_band(low_hz, high_hz, "band envelope");
  const std::vector<Complex> z = analytic_band(x, sample_rate_hz, low_hz, high_hz);
  std::vector<double> e(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) e[i] = std::abs(z[i]);
  return e;
}

Spectrum envelope_spectrum(const std::vector<double>& x, double sample_rate_hz, double low_hz, double high_hz) {
  return amplitude_spectrum(band_envelope(x, sample_rate_hz, low_hz, high_hz), sample_rate_hz);
}

std::vector<double> integrate_to_velocity(const std::vector<double>& accel, double sample_rate_hz, double low_hz,
                                          double high_hz) {
  check_signal(accel, sample_rate_hz, "velocity");
  check_band(low_hz, high_hz, "velocity");
  std::vector<Complex> spectrum = forward(accel);
  const std::size_t n = spectrum.size();
  const double df = sample_rate_hz / static_cast<double>(n);
  for (std::size_t k = 0; k < n; ++k) {
    // Bin k and its mirror n-k stand for the same |f|; the sign of omega follows the bin.
    const bool negative = 2 * k > n;
    const double f = (negative ? static_cast<double>(n - k) : static_cast<double>(k)) * df;
    if (k == 0 || 2 * k == n || !in_band(f, low_hz, high_hz)) {
      spectrum[k] = 0.0;
      continue;
    }
    const double omega = 2.0 * kPi * f * (negative ? -1.0 : 1.0);
    spectrum[k] /= Complex(0.0, omega);
  }
  std::vector<double> v;
  Eigen::FFT<double> fft;
  fft.inv(v, spectrum);
  return v;
}

double band_velocity_rms(const std::vector<double>& accel, double sample_rate_hz, double low_hz, double high_hz) {
  check_signal(accel, sample_rate_hz, "velocity RMS");
  check_band(low_hz, high_hz, "velocity RMS");
  const std::size_t n = accel.size();
  const double m = mean_of(accel);
  const std::vector<double> w = hann(n);
  double window_energy = 0.0;
  std::vector<double> windowed(n);
  for (std::size_t i = 0; i < n; ++i) {
    windowed[i] = (accel[i] - m) * w[i];
    window_energy += w[i] * w[i];
  }
  std::vector<Complex> spectrum;
  Eigen::FFT<double> fft;
  fft.fwd(spectrum, windowed);
  const double df = sample_rate_hz / static_cast<double>(n);
  long double sum = 0.0L;
  for (std::size_t k = 1; 2 * k < n; ++k) {
    const double f = k * df;
    if (!in_band(f, low_hz, high_hz)) continue;
    const double omega = 2.0 * kPi * f;
    sum += 2.0L * std::norm(spectrum[k]) / (static_cast<long double>(omega) * omega);  // both sides
  }
  return std::sqrt(static_cast<double>(sum / (static_cast<long double>(n) * window_energy)));
}

namespace {
// The kurtogram's taper: a cosine over kTaper of the window at each end. The band filters
// are circular: the jump between the window's last and first sample is a click that rings
// in every band and, in the bands above a sensor's anti-alias cut-off where nothing else is
// left, reads as the most impulsive signal. The taper removes the jump, and the moments
// leave out the tapered ends of each band's envelope.
constexpr double kTaper = 0.05;

// Spectrum of the mean-removed, Tukey-tapered window.
std::vector<Complex> tapered_spectrum(const std::vector<double>& x) {
  const std::size_t samples = x.size();
  const double mean = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(samples);
  const std::size_t ramp = static_cast<std::size_t>(kTaper * static_cast<double>(samples));
  std::vector<double> tapered(samples);
  for (std::size_t i = 0; i < samples; ++i) {
    const std::size_t from_end = std::min(i, samples - 1 - i);
    const double w =
        from_end >= ramp
            ? 1.0
            : 0.5 * (1.0 - std::cos(kPi * (static_cast<double>(from_end) + 0.5) / static_cast<double>(ramp)));
    tapered[i] = (x[i] - mean) * w;
  }
  return forward(tapered);
}

// Spectral kurtosis <|c|^4> / <|c|^2>^2 - 2 of the complex envelope c of the band [low, high)
// of a tapered spectrum: the band's bins moved to baseband, zero-padded to a power of two
// >= 2 x their count, inverse-transformed, the tapered ends left out. Also the number of
// bins (independent complex samples). False when the band holds too few bins.
// With a floor density d > 0 (units/sqrt(Hz)) the kurtosis is the one the band would show
// with white noise of that density added: independent circular Gaussian noise of power
// P_n beside a band power P_c scales it by (P_c / (P_c + P_n))^2 (Antoni, MSSP 20, 2006).
bool band_kurtosis(const std::vector<Complex>& spectrum, double fs, double low_hz, double high_hz, double floor_density,
                   double* kurtosis, std::size_t* bins) {
  const std::size_t n = spectrum.size();
  const double df = fs / static_cast<double>(n);
  // Bins in [low, high) (the last band up to, not including, Nyquist; never DC).
  const auto k0 = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(low_hz / df)));
  std::size_t k1 = static_cast<std::size_t>(std::ceil(high_hz / df));  // one past
  k1 = std::min(k1, (n + 1) / 2);
  if (k1 <= k0 + 8) return false;  // too few bins for a kurtosis
  const std::size_t count = k1 - k0;
  std::size_t m = 16;
  while (m < 2 * count) m *= 2;
  std::vector<Complex> band(m, Complex(0.0, 0.0));
  for (std::size_t j = 0; j < count; ++j) band[j] = spectrum[k0 + j];
  std::vector<Complex> envelope;
  Eigen::FFT<double> fft;
  fft.inv(envelope, band);
  // The envelope spans the window in m samples: its tapered ends are left out.
  const std::size_t skip = static_cast<std::size_t>(std::ceil(kTaper * static_cast<double>(m)));
  long double m2 = 0.0L, m4 = 0.0L;
  for (std::size_t j = skip; j + skip < m; ++j) {
    const long double p = std::norm(envelope[j]);
    m2 += p;
    m4 += p * p;
  }
  m2 /= static_cast<long double>(m - 2 * skip);
  m4 /= static_cast<long double>(m - 2 * skip);
  // The floor's envelope power: each of the count bins has E|X|^2 = n (fs / 2) d^2 in the
  // untapered middle of the window, and the inverse transform divides by m.
  const long double noise = static_cast<long double>(count) * 0.5L * static_cast<long double>(n) * fs * floor_density *
                            floor_density / (static_cast<long double>(m) * m);
  const long double share = m2 > 0.0L ? m2 / (m2 + noise) : 0.0L;
  *kurtosis = m2 > 0.0L ? static_cast<double>((m4 / (m2 * m2) - 2.0L) * share * share) : 0.0;
  *bins = count;
  return true;
}

// The tapered ends carry no weight: (1 - 2 kTaper) of a band's bins are independent.
double independent_samples(std::size_t bins) { return static_cast<double>(bins) * (1.0 - 2.0 * kTaper); }
}  // namespace

BandKurtosis band_spectral_kurtosis(const std::vector<double>& x, double fs, double low_hz, double high_hz,
                                    double floor_density) {
  check_signal(x, fs, "band kurtosis");
  check_band(low_hz, high_hz, "band kurtosis");
  BandKurtosis b;
  std::size_t bins = 0;
  b.valid = band_kurtosis(tapered_spectrum(x), fs, low_hz, high_hz, floor_density, &b.kurtosis, &bins);
  b.independent_samples = independent_samples(bins);
  return b;
}

Kurtogram fast_kurtogram(const std::vector<double>& x, double fs, double min_width_hz, double min_low_hz, int max_bands,
                         double floor_density) {
  check_signal(x, fs, "kurtogram");
  const std::vector<Complex> spectrum = tapered_spectrum(x);
  const double nyquist = 0.5 * fs;
  Kurtogram k;
  bool have_best = false;
  // 1, 2, 3, 4, 6, 8, 12, 16, 24, ...: the binary levels 2^j and the 1/3 levels 3 x 2^(j-1).
  for (int binary = 1; binary <= max_bands; binary *= 2) {
    for (int nb : {binary, binary * 3 / 2}) {
      if (nb > max_bands || (binary == 1 && nb != 1)) continue;
      const double width = nyquist / nb;
      if (width < min_width_hz) continue;
      for (int i = 0; i < nb; ++i) {
        KurtogramBand b;
        b.bands_in_level = nb;
        b.low_hz = i * width;
        b.high_hz = (i + 1) * width;
        if (b.low_hz < min_low_hz) continue;
        std::size_t bins = 0;
        if (!band_kurtosis(spectrum, fs, b.low_hz, b.high_hz, floor_density, &b.kurtosis, &bins)) continue;
        b.independent_samples = independent_samples(bins);
        k.bands.push_back(b);
        if (!have_best || b.kurtosis > k.best.kurtosis) {
          k.best = b;
          have_best = true;
        }
      }
    }
  }
  if (!have_best)
    throw InvalidInputError("kurtogram: no band of at least " + std::to_string(min_width_hz) + " Hz above " +
                            std::to_string(min_low_hz) + " Hz fits below the Nyquist frequency");
  return k;
}

SpectralPeak find_peak(const Spectrum& s, double expected_hz, const PeakSearchOptions& o, double absolute_floor) {
  SpectralPeak p;
  p.expected_hz = expected_hz;
  const auto bins = static_cast<long>(s.amplitude.size());
  if (!(s.resolution_hz > 0.0) || bins < 8 || !(expected_hz > 0.0) || !std::isfinite(expected_hz)) return p;
  const double centre = expected_hz / s.resolution_hz;
  const double half = std::max(o.tolerance_rel * centre, static_cast<double>(o.tolerance_min_bins));
  const long lo = std::max(1L, static_cast<long>(std::ceil(centre - half)));
  const long hi = std::min(bins - 2, static_cast<long>(std::floor(centre + half)));
  if (lo > hi) return p;
  long k = lo;
  for (long j = lo; j <= hi; ++j)
    if (s.amplitude[j] > s.amplitude[k]) k = j;
  const auto is_local_maximum = [&](long j) {
    return s.amplitude[j] >= s.amplitude[j - 1] && s.amplitude[j] >= s.amplitude[j + 1];
  };
  // Gaussian (log-parabolic) interpolation, exact for a Gaussian lobe and within a few
  // hundredths of a bin for the Hann lobe: the line's position in bins.
  const auto line_bins = [&](long j) {
    double offset = 0.0;
    const double a0 = s.amplitude[j - 1], a1 = s.amplitude[j], a2 = s.amplitude[j + 1];
    if (a0 > 0.0 && a1 > 0.0 && a2 > 0.0) {
      const double l0 = std::log(a0), l1 = std::log(a1), l2 = std::log(a2);
      const double denom = l0 - 2.0 * l1 + l2;
      if (denom < 0.0) offset = std::clamp(0.5 * (l0 - l2) / denom, -0.5, 0.5);
    }
    return static_cast<double>(j) + offset;
  };
  // A line within the window whose largest bin lies just outside it (the line between the
  // window's last bin and the next): the largest bin inside is its flank. The line is the
  // one searched when its interpolated frequency lies within the window (docs/health.md,
  // "Envelope analysis", step 4).
  const long out = k == hi && hi + 1 <= bins - 2 ? hi + 1 : k == lo && lo - 1 >= 1 ? lo - 1 : -1;
  if (out > 0 && s.amplitude[out] > s.amplitude[k] && is_local_maximum(out) &&
      std::abs(line_bins(out) - centre) <= half)
    k = out;
  p.searched = true;
  p.amplitude = s.amplitude[k];
  p.local_maximum = is_local_maximum(k);
  p.frequency_hz = line_bins(k) * s.resolution_hz;
  std::vector<double> neighbours;
  for (long j = std::max(1L, k - o.noise_half_width_bins); j <= std::min(bins - 1, k + o.noise_half_width_bins); ++j)
    if (std::abs(j - k) > o.noise_exclude_bins) neighbours.push_back(s.amplitude[j]);
  if (!neighbours.empty()) {
    auto mid = neighbours.begin() + static_cast<long>(neighbours.size() / 2);
    std::nth_element(neighbours.begin(), mid, neighbours.end());
    p.noise_floor = *mid;
  }
  const double floor = std::max(p.noise_floor, absolute_floor);
  p.snr_db = floor > 0.0 ? 20.0 * std::log10(p.amplitude / floor) : std::numeric_limits<double>::infinity();
  return p;
}

}  // namespace bearing_sim

namespace bearing_sim {

namespace {
// The share of bins below floor in the Hann-windowed spectrum (window scaled to unit RMS, so
// white noise has the bin magnitudes of the plain transform). Counted with a window because
// a strong line's leakage in the plain transform falls only as 1/distance: the lines of a
// noise-free periodic signal would fill every bin with leakage and pass for a noise floor.
double share_of_bins_below(const std::vector<double>& x, double floor) {
  const std::vector<double> w = hann(x.size());
  std::vector<double> windowed(x.size());
  const double unit_rms = std::sqrt(8.0 / 3.0);  // the periodic Hann window's energy is 3/8
  const double m = mean_of(x);
  for (std::size_t i = 0; i < x.size(); ++i) windowed[i] = unit_rms * w[i] * (x[i] - m);
  const std::vector<Complex> spectrum = forward(windowed);
  std::size_t below = 0;
  for (const Complex& c : spectrum) below += std::abs(c) < floor ? 1 : 0;
  return static_cast<double>(below) / static_cast<double>(spectrum.size());
}
}  // namespace

std::vector<double> prewhiten(const std::vector<double>& x, double floor_per_bin, double* share_below_floor) {
  check_signal(x, 1.0, "prewhiten");
  std::vector<Complex> spectrum = forward(x);
  const double floor = std::max(floor_per_bin, std::numeric_limits<double>::min());
  if (share_below_floor) *share_below_floor = share_of_bins_below(x, floor);
  for (Complex& c : spectrum) c /= std::max(std::abs(c), floor);
  std::vector<Complex> z;
  Eigen::FFT<double> fft;
  fft.inv(z, spectrum);
  std::vector<double> y(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) y[i] = z[i].real();
  return y;
}

double white_noise_bin_magnitude(double density_per_sqrt_hz, std::size_t n, double sample_rate_hz) {
  return density_per_sqrt_hz * std::sqrt(0.5 * static_cast<double>(n) * sample_rate_hz);
}

Spectrum averaged_envelope_spectrum(const std::vector<double>& x, double fs, double low_hz, double high_hz,
                                    std::size_t segment_samples, std::size_t* segments_out, double* envelope_mean_out) {
  const std::vector<double> envelope = band_envelope(x, fs, low_hz, high_hz);
  if (envelope_mean_out) *envelope_mean_out = mean_of(envelope);
  const std::size_t n = std::min(std::max<std::size_t>(segment_samples, 8), envelope.size());
  const std::size_t step = std::max<std::size_t>(n / 2, 1);
  Spectrum sum;
  std::size_t segments = 0;
  for (std::size_t start = 0; start + n <= envelope.size(); start += step) {
    const std::vector<double> segment(envelope.begin() + static_cast<long>(start),
                                      envelope.begin() + static_cast<long>(start + n));
    const Spectrum s = amplitude_spectrum(segment, fs);
    if (sum.amplitude.empty()) {
      sum.resolution_hz = s.resolution_hz;
      sum.amplitude.assign(s.amplitude.size(), 0.0);
    }
    for (std::size_t k = 0; k < s.amplitude.size(); ++k) sum.amplitude[k] += s.amplitude[k] * s.amplitude[k];
    ++segments;
  }
  for (double& a : sum.amplitude) a = std::sqrt(a / static_cast<double>(segments));
  if (segments_out) *segments_out = segments;
  return sum;
}

double equivalent_averages(std::size_t segments) {
  constexpr double kHannHalfOverlapCorrelation = 0.167;
  return segments > 1
             ? static_cast<double>(segments) / (1.0 + 2.0 * kHannHalfOverlapCorrelation * kHannHalfOverlapCorrelation)
             : static_cast<double>(segments);
}

namespace {
// P(Gamma(k, 1/k) > x) for a whole k >= 1: exp(-k x) sum_{j<k} (k x)^j / j!.
double gamma_mean_one_exceedance(int k, double x) {
  const double y = k * x;
  double term = 1.0, sum = 1.0;
  for (int j = 1; j < k; ++j) {
    term *= y / j;
    sum += term;
  }
  return std::exp(-y) * sum;
}
// The x where the (decreasing) exceedance equals p, by bisection on a bracketing interval.
double gamma_mean_one_quantile(int k, double p) {
  double lo = 0.0, hi = 1.0;
  while (gamma_mean_one_exceedance(k, hi) > p) hi *= 2.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (gamma_mean_one_exceedance(k, mid) > p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}
}  // namespace

double averaged_threshold_db(double single_threshold_db, double averages) {
  const int k = std::max(1, static_cast<int>(std::floor(averages)));
  if (k == 1) return single_threshold_db;
  // One spectrum: power exponential, median ln 2 of the mean; P(power > r median) = 2^-r.
  const double ratio = std::pow(10.0, single_threshold_db / 10.0);
  const double p = std::exp(-ratio * std::log(2.0));
  const double threshold = gamma_mean_one_quantile(k, p), median = gamma_mean_one_quantile(k, 0.5);
  return 10.0 * std::log10(threshold / median);  // a power ratio: dB of amplitude
}

double line_chance(const Spectrum& s, const SpectralPeak& peak, double window_half_hz,
                   const std::vector<double>& own_lines_hz, double neighbourhood_rel, const PeakSearchOptions& o) {
  const auto bins = static_cast<long>(s.amplitude.size());
  if (!peak.searched || !(s.resolution_hz > 0.0) || bins < 8) return 1.0;
  const double df = s.resolution_hz, f0 = peak.expected_hz;
  const double reach = std::max(neighbourhood_rel * f0, o.noise_half_width_bins * df);
  const double guard = o.noise_exclude_bins * df;  // a line's Hann main lobe beside its window
  const auto excluded = [&](double f) {
    if (std::abs(f - f0) <= window_half_hz + guard) return true;
    for (double l : own_lines_hz)
      if (std::abs(f - l) <= std::max(o.tolerance_rel * l, o.tolerance_min_bins * df) + guard) return true;
    return false;
  };
  long counted_bins = 0, higher_maxima = 0;
  for (long j = std::max(1L, static_cast<long>(std::ceil((f0 - reach) / df)));
       j <= std::min(bins - 2, static_cast<long>(std::floor((f0 + reach) / df))); ++j) {
    const double f = j * df;
    if (excluded(f)) continue;
    ++counted_bins;
    const double a = s.amplitude[static_cast<std::size_t>(j)];
    if (a >= peak.amplitude && a >= s.amplitude[static_cast<std::size_t>(j - 1)] &&
        a >= s.amplitude[static_cast<std::size_t>(j + 1)])
      ++higher_maxima;
  }
  if (counted_bins == 0) return 1.0;
  const double rate_per_hz = (higher_maxima + 0.5) / (counted_bins * df);
  return 1.0 - std::exp(-rate_per_hz * 2.0 * window_half_hz);
}

}  // namespace bearing_sim
