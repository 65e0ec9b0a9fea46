#include "bearing_sim/core/signal_statistics.hpp"

#include <cmath>
#include <string>

#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {

SignalStatistics signal_statistics(const std::vector<double>& x, std::size_t begin, std::size_t end) {
  if (end > x.size() || begin >= end) throw InvalidInputError("signal statistics: empty or out-of-range sample window");
  SignalStatistics s;
  s.samples = end - begin;
  // Two passes: the mean first, then the central moments (a one-pass sum of x^4 loses
  // the kurtosis of a small signal on a large offset).
  long double sum = 0.0L;
  for (std::size_t i = begin; i < end; ++i) {
    if (!std::isfinite(x[i])) throw InvalidInputError("signal statistics: sample " + std::to_string(i) + " is not finite");
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
