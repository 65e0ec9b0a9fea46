#pragma once
// Time-domain statistics of a vibration signal (docs/model.md section 13, condition indicators).
// All of them are taken about the mean of the samples: an accelerometer is AC-coupled,
// and an offset (gravity, a DC drift) says nothing about the bearing.
#include <cstddef>
#include <vector>

namespace bearing_sim {

struct SignalStatistics {
  std::size_t samples = 0;
  double mean = 0.0;
  double rms = 0.0;           // about the mean
  double peak = 0.0;          // largest |x - mean|
  double crest_factor = 0.0;  // peak / rms (sqrt 2 for a sine); 0 for a constant signal
  double kurtosis = 0.0;      // m4 / m2^2, NOT the excess: 3 for Gaussian noise, 1.5 for a sine
};

// Over samples [begin, end) of x; throws InvalidInputError for an empty range or a
// non-finite sample.
SignalStatistics signal_statistics(const std::vector<double>& x, std::size_t begin, std::size_t end);
inline SignalStatistics signal_statistics(const std::vector<double>& x) { return signal_statistics(x, 0, x.size()); }

// The same statistics one sample at a time, for runs too long to store: the mean and the
// central moment sums updated as in Welford (1962) and Pebay (2008), safe for a small signal
// on a large mean (a voltage output's bias). The peak is about the final mean.
class StreamedStatistics {
 public:
  void add(double x);
  std::size_t samples() const { return n_; }
  // samples = 0 gives zeros.
  SignalStatistics statistics() const;

 private:
  std::size_t n_ = 0;
  double mean_ = 0.0, m2_ = 0.0, m3_ = 0.0, m4_ = 0.0;
  double min_ = 0.0, max_ = 0.0;
};

// Shorthands over the whole vector (about the mean).
double signal_rms(const std::vector<double>& x);
double signal_peak(const std::vector<double>& x);
double crest_factor(const std::vector<double>& x);
double kurtosis(const std::vector<double>& x);

}  // namespace bearing_sim
