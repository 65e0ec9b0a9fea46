#pragma once
// Rule 14 of the diagnosis (docs/health.md): the times between consecutive impacts in a band
// envelope, counted against one period. A spalled ball strikes in short runs (its spin axis
// wanders, so the pit meets the races only on some passes) at a rate that changes from run to
// run by the ball's slip; its envelope line smears beyond a line's window while each run keeps
// the interval 1 / (2 x BSF).
#include <cstddef>
#include <vector>

#include "bearing_sim/core/condition_indicators.hpp"

namespace bearing_sim {

// Poisson P(N >= k) for mean `mean` >= 0.
double poisson_upper_tail(std::size_t k, double mean);

// The intervals of `band_envelope` (sampled at sample_rate_hz) against period_s: impacts are
// its local maxima over t.impact_over_median x its median, the highest kept where two lie
// closer than half the period.
ImpactIntervals impact_intervals(const std::vector<double>& band_envelope, double sample_rate_hz, double period_s,
                                 const DiagnosisThresholds& t);

}  // namespace bearing_sim
