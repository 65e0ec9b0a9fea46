#include "bearing_sim/core/speed_estimate.hpp"

#include <algorithm>
#include <cmath>

#include "bearing_sim/core/spectrum.hpp"

namespace bearing_sim {

SpeedEstimate estimate_speed_scale(const std::vector<double>& x, double fs, double ring_hz,
                                   const SpeedEstimateOptions& o) {
  SpeedEstimate e;
  if (!(ring_hz > 0.0) || x.size() < 64) return e;
  const Spectrum s = amplitude_spectrum(x, fs);
  if (!(o.tolerance_rel * ring_hz >= 2.0 * s.resolution_hz)) return e;  // the window too narrow to search
  PeakSearchOptions search;
  search.tolerance_rel = o.tolerance_rel;
  std::vector<double> clear;
  for (int h = 1; h <= 3; ++h) {
    const SpectralPeak p = find_peak(s, h * ring_hz, search);
    if (!p.searched || !p.local_maximum || p.snr_db < o.line_snr_db) continue;
    e.implied_scale[h - 1] = p.frequency_hz / (h * ring_hz);
    clear.push_back(e.implied_scale[h - 1]);
  }
  if (clear.size() < 2) return e;
  std::vector<double> sorted = clear;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted.size() == 2 ? 0.5 * (sorted[0] + sorted[1]) : sorted[1];
  double sum = 0.0;
  int agreeing = 0;
  for (double v : clear)
    if (std::abs(v - median) <= o.agreement_rel * median) {
      sum += v;
      ++agreeing;
    }
  if (agreeing < 2) return e;
  e.measured = true;
  e.scale = sum / agreeing;
  return e;
}

BearingFrequencies scaled_frequencies(const BearingFrequencies& f, double s) {
  BearingFrequencies g = f;
  g.cage_hz *= s;
  g.ball_pass_outer_race_hz *= s;
  g.ball_pass_inner_race_hz *= s;
  g.ball_spin_hz *= s;
  g.relative_ring_hz *= s;
  g.varying_compliance_hz *= s;
  g.inner_ring_hz *= s;
  g.outer_ring_hz *= s;
  return g;
}

}  // namespace bearing_sim
