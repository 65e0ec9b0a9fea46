#include "bearing_sim/core/signal_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {

void StreamedStatistics::add(double x) {
  const double previous = static_cast<double>(n_);
  ++n_;
  const double n = static_cast<double>(n_);
  const double delta = x - mean_, delta_n = delta / n, delta_n2 = delta_n * delta_n;
  const double term = delta * delta_n * previous;
  mean_ += delta_n;
  // M4 and M3 from the old M2 and M3 (Pebay); M2 in Welford's form delta (x - new mean).
  m4_ += term * delta_n2 * (n * n - 3.0 * n + 3.0) + 6.0 * delta_n2 * m2_ - 4.0 * delta_n * m3_;
  m3_ += term * delta_n * (n - 2.0) - 3.0 * delta_n * m2_;
  m2_ += delta * (x - mean_);
  min_ = n_ == 1 ? x : std::min(min_, x);
  max_ = n_ == 1 ? x : std::max(max_, x);
}

SignalStatistics StreamedStatistics::statistics() const {
  SignalStatistics s;
  s.samples = n_;
  if (n_ == 0) return s;
  s.mean = mean_;
  s.rms = std::sqrt(m2_ / static_cast<double>(n_));
  s.peak = std::max(max_ - mean_, mean_ - min_);
  if (m2_ > 0.0) {
    s.crest_factor = s.peak / s.rms;
    s.kurtosis = static_cast<double>(n_) * m4_ / (m2_ * m2_);
  }
  return s;
}

SignalStatistics signal_statistics(const std::vector<double>& x, std::size_t begin, std::size_t end) {
  if (end > x.size() || begin >= end) throw InvalidInputError("signal statistics: empty or out-of-range sample window");
  SignalStatistics s;
  s.samples = end - begin;
  // Two passes: the mean first, then the central moments (a one-pass sum of x^4 loses
  // the kurtosis of a small signal on a large offset).
  long double sum = 0.0L;
  for (std::size_t i = begin; i < end; ++i) {
    if (!std::isfinite(x[i]))
      throw InvalidInputError("signal statistics: sample " + std::to_string(i) + " is not finite");
    sum += x[i];
  }
  s.mean = static_cast<double>(sum / static_cast<long double>(s.samples));
  long double m2 = 0.0L, m4 = 0.0L;
  double peak = 0.0;
  for (std::size_t i = begin; i < end; ++i) {
    const double d = x[i] - s.mean;
    const long double d2 = static_cast<long double>(d) * d;
    m2 += d2;
    m4 += d2 * d2;
    peak = std::max(peak, std::abs(d));
  }
  m2 /= static_cast<long double>(s.samples);
  m4 /= static_cast<long double>(s.samples);
  s.rms = std::sqrt(static_cast<double>(m2));
  s.peak = peak;
  if (m2 > 0.0L) {
    s.crest_factor = peak / s.rms;
    s.kurtosis = static_cast<double>(m4 / (m2 * m2));
  }
  return s;
}

double signal_rms(const std::vector<double>& x) { return signal_statistics(x).rms; }
double signal_peak(const std::vector<double>& x) { return signal_statistics(x).peak; }
double crest_factor(const std::vector<double>& x) { return signal_statistics(x).crest_factor; }
double kurtosis(const std::vector<double>& x) { return signal_statistics(x).kurtosis; }

}  // namespace bearing_sim
