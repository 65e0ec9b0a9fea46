#pragma once
// Vibration acceleration level L (JB/T 5314) and the statistics it rests on.
#include <cstddef>
#include <vector>

namespace bearing_sim {

constexpr double kReferenceAcceleration_m_s2 = 9.81e-3;  // a0 of JB/T 5314

// L = 20 lg(a_rms / a0), dB. A zero RMS gives -infinity.
double vibration_level_db(double accel_rms_m_s2);

// RMS about the mean of samples [begin, end).
double rms_about_mean(const std::vector<double>& x, std::size_t begin, std::size_t end);
double mean(const std::vector<double>& x, std::size_t begin, std::size_t end);

// RMS about the mean over a sliding window of fixed length, O(1) per sample.
class RunningRms {
 public:
  explicit RunningRms(std::size_t window_samples);
  void add(double x);
  double rms() const;  // over the samples held so far (at most the window)
  std::size_t size() const { return count_; }
  std::size_t window() const { return buffer_.size(); }
  void resize(std::size_t window_samples);

 private:
  std::vector<double> buffer_;
  std::size_t next_ = 0, count_ = 0;
  long double sum_ = 0.0L, sum_sq_ = 0.0L;
};

}  // namespace bearing_sim
