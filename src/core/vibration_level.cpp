#include "bearing_sim/core/vibration_level.hpp"

#include <cmath>
#include <limits>

#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {

double vibration_level_db(double accel_rms_m_s2) {
  if (!(accel_rms_m_s2 >= 0.0)) throw InvalidInputError("acceleration RMS must be >= 0");
  if (accel_rms_m_s2 == 0.0) return -std::numeric_limits<double>::infinity();
  return 20.0 * std::log10(accel_rms_m_s2 / kReferenceAcceleration_m_s2);
}

double mean(const std::vector<double>& x, std::size_t begin, std::size_t end) {
  if (end <= begin || end > x.size()) throw InvalidInputError("mean: empty or invalid range");
  double s = 0.0;
  for (std::size_t i = begin; i < end; ++i) s += x[i];
  return s / static_cast<double>(end - begin);
}

double rms_about_mean(const std::vector<double>& x, std::size_t begin, std::size_t end) {
  const double m = mean(x, begin, end);
  double s = 0.0;
  for (std::size_t i = begin; i < end; ++i) s += (x[i] - m) * (x[i] - m);
  return std::sqrt(s / static_cast<double>(end - begin));
}

RunningRms::RunningRms(std::size_t window_samples) { resize(window_samples); }

void RunningRms::resize(std::size_t window_samples) {
  if (window_samples == 0) throw InvalidInputError("RMS window must hold at least one sample");
  buffer_.assign(window_samples, 0.0);
  next_ = count_ = 0;
  sum_ = sum_sq_ = 0.0L;
}

void RunningRms::add(double x) {
  if (count_ == buffer_.size()) {
    const double old = buffer_[next_];
    sum_ -= old;
    sum_sq_ -= static_cast<long double>(old) * old;
  } else {
    ++count_;
  }
  buffer_[next_] = x;
  sum_ += x;
  sum_sq_ += static_cast<long double>(x) * x;
  next_ = (next_ + 1) % buffer_.size();
  if (next_ == 0) {
    // Resum once per window so rounding in the running update cannot drift.
    sum_ = sum_sq_ = 0.0L;
    for (std::size_t i = 0; i < count_; ++i) {
      sum_ += buffer_[i];
      sum_sq_ += static_cast<long double>(buffer_[i]) * buffer_[i];
    }
  }
}

double RunningRms::rms() const {
  if (count_ == 0) return 0.0;
  const long double n = static_cast<long double>(count_);
  const long double var = sum_sq_ / n - (sum_ / n) * (sum_ / n);
  return var > 0.0L ? static_cast<double>(std::sqrt(var)) : 0.0;
}

}  // namespace bearing_sim
