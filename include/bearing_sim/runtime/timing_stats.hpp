#pragma once
// Percentiles of recent chunk timings (publish lateness) over a fixed ring buffer (ROS-free).
#include <cstddef>
#include <vector>

namespace bearing_sim {
namespace runtime {

class TimingStats {
 public:
  explicit TimingStats(std::size_t capacity = 6000);
  void add(double value);
  // p in [0, 1], nearest-rank; 0 if empty.
  double percentile(double p) const;
  double max() const;
  std::size_t size() const { return count_; }
  void clear();

 private:
  std::vector<double> values_;
  std::size_t next_ = 0, count_ = 0;
};

}  // namespace runtime
}  // namespace bearing_sim
