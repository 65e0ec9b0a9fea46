#include "bearing_sim/runtime/timing_stats.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bearing_sim {
namespace runtime {

TimingStats::TimingStats(std::size_t capacity) : values_(capacity) {
  if (capacity == 0) throw std::invalid_argument("timing stats need a capacity");
}

void TimingStats::add(double value) {
  values_[next_] = value;
  next_ = (next_ + 1) % values_.size();
  count_ = std::min(count_ + 1, values_.size());
}

double TimingStats::percentile(double p) const {
  if (count_ == 0) return 0.0;
  std::vector<double> v(values_.begin(), values_.begin() + static_cast<std::ptrdiff_t>(count_));
  const std::size_t rank = static_cast<std::size_t>(std::ceil(std::clamp(p, 0.0, 1.0) * static_cast<double>(count_)));
  const std::size_t k = rank == 0 ? 0 : rank - 1;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

double TimingStats::max() const {
  if (count_ == 0) return 0.0;
  return *std::max_element(values_.begin(), values_.begin() + static_cast<std::ptrdiff_t>(count_));
}

void TimingStats::clear() { next_ = count_ = 0; }

}  // namespace runtime
}  // namespace bearing_sim
