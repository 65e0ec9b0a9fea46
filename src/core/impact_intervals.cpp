#include "impact_intervals.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace bearing_sim {

double poisson_upper_tail(std::size_t k, double mean) {
  if (k == 0) return 1.0;
  if (!(mean > 0.0)) return 0.0;
  const auto log_term = [mean](double j) { return -mean + j * std::log(mean) - std::lgamma(j + 1.0); };
  const double kk = static_cast<double>(k);
  double sum = 0.0;
  if (kk > mean) {  // the tail's terms fall from the first: sum them
    for (double j = kk;; j += 1.0) {
      const double term = std::exp(log_term(j));
      sum += term;
      if (term <= 1e-17 * sum || j > kk + 1e6) break;
    }
    return std::min(1.0, sum);
  }
  for (double j = 0.0; j < kk; j += 1.0) sum += std::exp(log_term(j));  // 1 - the head
  return std::clamp(1.0 - sum, 0.0, 1.0);
}

ImpactIntervals impact_intervals(const std::vector<double>& e, double fs, double period_s,
                                 const DiagnosisThresholds& t) {
  ImpactIntervals r;
  r.tested = true;
  r.period_s = period_s;
  const double period = period_s * fs;  // samples
  if (e.size() < 3 || !(period >= 2.0)) return r;
  std::vector<double> sorted = e;
  const auto middle = sorted.begin() + static_cast<long>(sorted.size() / 2);
  std::nth_element(sorted.begin(), middle, sorted.end());
  const double threshold = t.impact_over_median * *middle;
  if (!(threshold > 0.0)) return r;
  std::vector<std::size_t> maxima;
  for (std::size_t i = 1; i + 1 < e.size(); ++i)
    if (e[i] > threshold && e[i] >= e[i - 1] && e[i] > e[i + 1]) maxima.push_back(i);
  // One impact per burst: the highest maxima first, none within half a period of a kept one.
  std::sort(maxima.begin(), maxima.end(), [&e](std::size_t a, std::size_t b) { return e[a] > e[b]; });
  const auto separation = static_cast<std::size_t>(std::llround(0.5 * period));
  std::set<std::size_t> kept;
  for (std::size_t i : maxima) {
    const auto next = kept.lower_bound(i);
    if (next != kept.end() && *next - i < separation) continue;
    if (next != kept.begin() && i - *std::prev(next) < separation) continue;
    kept.insert(i);
  }
  r.impacts = kept.size();
  const double tol = t.interval_tolerance;
  std::vector<double> in_window;
  for (auto a = kept.begin(), b = std::next(a); a != kept.end() && b != kept.end(); ++a, ++b) {
    const double ratio = static_cast<double>(*b - *a) / period;
    const double off = std::abs(ratio - 1.0);
    if (off < tol)
      in_window.push_back(ratio);
    else if (off < 4.0 * tol)
      ++r.around;
  }
  r.in_window = in_window.size();
  if (!in_window.empty()) {
    const auto mid = in_window.begin() + static_cast<long>(in_window.size() / 2);
    std::nth_element(in_window.begin(), mid, in_window.end());
    r.median_ratio = *mid;
  }
  // The neighbourhood is 3 windows wide; the half keeps an empty one from giving certainty.
  r.expected = (static_cast<double>(r.around) + 0.5) / 3.0;
  r.chance = poisson_upper_tail(r.in_window, r.expected);
  r.found = static_cast<double>(r.in_window) >= t.intervals_min && r.chance <= t.interval_chance_max &&
            std::abs(r.median_ratio - 1.0) <= 0.5 * tol;
  return r;
}

}  // namespace bearing_sim
